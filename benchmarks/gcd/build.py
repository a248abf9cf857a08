"""Build the GarmentCode design benchmark's cases: sample, size, place by the spec, drape with newton.

Per seed of the manifest: GarmentCode's sampler (``sample_designs.py``, run as a subprocess with
this Python) draws ``count`` designs sized to the seed's body (its measurement .yaml in cm), and
each design becomes a case folder (FORMATS.md):

- ``body.obj`` (+ ``skeleton.json`` for an anny body, as ``unsew body make`` writes them);
- ``target.obj``: the design sewn and draped by newton's Style3D solver (benchmarks/foreign/
  newton_drape.py) from the specification's own 3D placement: every panel vertex starts at
  ``R @ (u, v, 0) + t`` with the panel's ``rotation`` (XYZ Euler angles [deg], applied as
  ``Rz @ Ry @ Rx``, GarmentCode's ``euler_xyz_to_R``) and ``translation`` [cm -> m]; the
  specification's frame is the body's (Y up, facing +Z, feet at y = 0, cm); front and back
  panels bent around the body, start vertices inside the body moved out; the edges the design
  labels as what the garment hangs from (ATTACH_LABELS) held at the specification's height;
- ``meta.json`` without the garment type; ``pattern_gt.json`` (the specification);
- ``truth.json`` (type and structural choices from ``design_params.yaml``; the fit never reads it);
- ``design_params.yaml`` and ``preview.png``.

Every design is recorded in ``OUT/build.json`` with its status: ``built``, or ``failed`` with the
reason (meshing refused, newton diverged, a check failed); a failed case still counts.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import time
import warnings
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
MANIFEST = HERE / "manifest.json"
#: Lower garments have their waist held while gravity ramps in (newton_drape's ``lower``).
LOWER_TYPES = ("skirt", "pants", "shorts")
#: Acceptance of a drape (as the foreign benchmark's): share of vertices inside the body.
MAX_INSIDE = 0.005
#: ... and the share of the cloth's rest area stretched past MAX_STRETCH (largest principal
#: stretch - 1 of a triangle: a seam left open or a burst shows here). A share, as for the
#: vertices inside, not the single worst triangle: a gathered cuff or collar seam stretches a
#: few triangles past it in drapes that are otherwise sound (docs/decisions/049).
MAX_STRETCH = 1.0
MAX_OVERSTRETCHED = 0.005
#: Drapes that pass every check and were refused when their preview was looked at, with why.
REFUSED_ON_SIGHT = {
    "gc_s2_001": "refused on sight: its flared skirt stands out behind the body, in the air",
}
#: ... and how far below the ground (the plane under the body's lowest point, newton_drape's
#: ``ground``) cloth may reach [m]: a garment long enough lies on it, none goes through it.
GROUND_TOL = 0.01
#: ... and the height above the ground [m] below which cloth inside the body is not counted as
#: inside: the body stands on the ground, so cloth lying under a sole is inside it by construction
#: (trousers long enough reach the floor round the feet: docs/decisions/051).
UNDERFOOT = 0.01
#: ... and how far the garment's top may sink below the specification's placement of it [m]
#: (a bodice whose shoulder seams did not close slides down the torso).
MAX_DROP = 0.08
#: ... and the share of directions round the body's vertical axis the garment must cover at its
#: best-covered height (every garment encircles the torso somewhere; one that fell off does not).
MIN_WRAP = 0.9


def _shared() -> Path:
    """``shared/`` beside the checkout (the nearest folder above that holds it) or $UNSEW_SHARED."""
    if os.environ.get("UNSEW_SHARED"):
        return Path(os.environ["UNSEW_SHARED"])
    for up in HERE.parents:
        if (up / "shared" / "garmentcode").is_dir():
            return up / "shared"
    raise SystemExit("no shared/garmentcode found beside the repository (set UNSEW_SHARED)")


def manifest() -> dict:
    return json.loads(MANIFEST.read_text())


def case_ids(seeds=None, count=None) -> list[tuple[str, int, int]]:
    """[(case id, seed, index)] in order: gc_s{seed}_{index:03d}."""
    m = manifest()
    count = m["count"] if count is None else count
    out = []
    for s in m["seeds"]:
        if seeds is None or s["seed"] in seeds:
            out += [(f"gc_s{s['seed']}_{i:03d}", s["seed"], i) for i in range(count)]
    return out


def seed_entry(seed: int) -> dict:
    for s in manifest()["seeds"]:
        if s["seed"] == seed:
            return s
    raise SystemExit(f"seed {seed} is not in {MANIFEST}")


def _log(*a):
    print(*a, flush=True)


# ---------------------------------------------------------------- bodies


def make_body(entry: dict, root: Path) -> Path:
    """The body folder (body.obj [+ skeleton.json], body.yaml in GarmentCode's format, cm) of a
    manifest body, made once under ``root/_bodies``."""
    b = entry["body"]
    d = root / "_bodies" / b["name"]
    if (d / "body.yaml").is_file():
        return d
    d.parent.mkdir(parents=True, exist_ok=True)
    tmp = d.with_name(d.name + ".tmp")
    shutil.rmtree(tmp, ignore_errors=True)
    shared = _shared()
    if b["model"] == "garmentcode":
        tmp.mkdir()
        shutil.copyfile(shared / "foreign" / "bodies" / b["mesh"], tmp / "body.obj")
        shutil.copyfile(shared / "garmentcode" / "assets" / "bodies" / f"{b['yaml']}.yaml", tmp / "body.yaml")
    else:  # anny, as a user makes it
        cmd = [sys.executable, "-m", "unsew", "body", "make", "--pose", b.get("pose", "A"), "--out", str(tmp)]
        for k, v in b["phenotype"].items():
            cmd += ["--phenotype", f"{k}={v}"]
        r = subprocess.run(cmd, capture_output=True, text=True, check=False)
        if r.returncode:
            raise RuntimeError(f"unsew body make failed: {(r.stderr.strip().splitlines() or [''])[-1]}")
        (tmp / "body.yaml").write_text(anny_body_yaml(tmp, shared))
    shutil.rmtree(d, ignore_errors=True)
    tmp.rename(d)
    return d


def anny_body_yaml(folder: Path, shared: Path) -> str:
    """GarmentCode's body measurements (cm) for a body folder with body.obj + skeleton.json.

    Measured on the body (unsew.body.measure): height, bust, waist, hips, arm length, shoulder
    width, the waist level and the arm's angle below horizontal; the other GarmentCode
    measurements are GarmentCode's ``mean_all`` values scaled by the height ratio (lengths) or
    the bust/hip ratio (widths and girths of the upper / lower body)."""
    import yaml

    from unsew.body.body import load_body
    from unsew.body.measure import measure_body

    body = load_body(folder / "body.obj", folder / "skeleton.json")
    m = measure_body(body)
    ref = yaml.safe_load((shared / "garmentcode" / "assets" / "bodies" / "mean_all.yaml").read_text())["body"]
    cm = 100.0
    h = m.height * cm
    kh, kb, kw, kp = (
        h / ref["height"],
        m.bust * cm / ref["bust"],
        m.waist * cm / ref["waist"],
        m.hip * cm / ref["hips"],
    )
    out = dict(ref)
    for k in (
        "head_l",
        "armscye_depth",
        "bust_line",
        "vert_bust_line",
        "hips_line",
        "crotch_hip_diff",
        "waist_over_bust_line",
    ):
        out[k] = ref[k] * kh
    for k in ("back_width", "bust_points", "underbust", "neck_w"):
        out[k] = ref[k] * kb
    out["waist_back_width"] = ref["waist_back_width"] * kw
    for k in ("hip_back_width", "bum_points", "leg_circ"):
        out[k] = ref[k] * kp
    out["wrist"] = ref["wrist"] * kh
    sk = body.skeleton
    arm = sk.position("left_elbow") - sk.position("left_shoulder")
    out.update(
        height=h,
        bust=m.bust * cm,
        waist=m.waist * cm,
        hips=m.hip * cm,
        arm_length=m.arm_length * cm,
        shoulder_w=m.shoulder_width * cm,
        # GarmentCode: waist level = height - head_l - waist_line
        waist_line=h - out["head_l"] - m.waist_height * cm,
        arm_pose_angle=float(np.degrees(np.arctan2(-arm[1], abs(arm[0])))),
    )
    return yaml.safe_dump({"body": {k: round(float(v), 4) for k, v in sorted(out.items())}})


def read_body(folder: Path):
    """(verts (V, 3) float64 [m], faces (F, 3) int64) of a body folder's body.obj."""
    import trimesh

    m = trimesh.load(folder / "body.obj", process=False, force="mesh")
    return np.asarray(m.vertices, np.float64), np.asarray(m.faces, np.int64)


# ---------------------------------------------------------------- designs


def canonical_order(spec_path: Path) -> None:
    """Rewrite a GarmentCode specification with its panels sorted by name and its stitches sorted.

    GarmentCode builds a design's panels and stitches by walking ``set``s of its components
    (``BaseComponent._get_subcomponents``), hashed by object identity, so their order in the file
    changes from run to run (memory addresses) while their content is the same. Sorted, the file
    depends on the seed alone. ``panel_order`` (GarmentCode's own, by position) is kept.
    """
    spec = json.loads(spec_path.read_text())
    pattern = spec["pattern"]
    pattern["panels"] = dict(sorted(pattern["panels"].items()))
    pattern["stitches"] = sorted(
        pattern["stitches"], key=lambda st: json.dumps([json.dumps(s, sort_keys=True) for s in st])
    )
    spec_path.write_text(json.dumps(spec, indent=2))


def sample_seed(seed: int, count: int, body_dir: Path, out: Path) -> Path:
    """Run GarmentCode's sampler for one seed into ``out/_designs/s{seed}`` (skipped when done);
    each specification rewritten in a canonical order (``canonical_order``), with the sampler's
    string hashing fixed (``PYTHONHASHSEED=0``), so that the seed alone decides the files."""
    d = out / "_designs" / f"s{seed}"
    done = d / "sampled.json"
    if done.is_file() and json.loads(done.read_text()).get("count") == count:
        return d
    shutil.rmtree(d, ignore_errors=True)
    d.mkdir(parents=True)
    t0 = time.time()
    r = subprocess.run(
        [
            sys.executable,
            str(_shared() / "garmentcode" / "sample_designs.py"),
            "--seed",
            str(seed),
            "--count",
            str(count),
            "--body",
            str(body_dir / "body.yaml"),
            "--out",
            str(d),
        ],
        capture_output=True,
        text=True,
        check=False,
        env=dict(os.environ, PYTHONHASHSEED="0"),
    )
    if r.returncode:
        raise RuntimeError(f"sample_designs.py failed: {(r.stderr.strip().splitlines() or [''])[-1]}")
    for spec_path in sorted(d.glob("*/*_specification.json")):
        canonical_order(spec_path)
    lines = [json.loads(ln) for ln in r.stdout.splitlines() if ln.startswith("{")]
    done.write_text(
        json.dumps({"count": count, "seconds": round(time.time() - t0, 1), "log": lines}, indent=1)
    )
    return d


def spec_rotation(angles_deg) -> np.ndarray:
    """GarmentCode's panel rotation: XYZ Euler angles [deg] -> (3, 3), ``Rz @ Ry @ Rx``
    (pygarment.pattern.rotation.euler_xyz_to_R, which its mesh generator applies)."""
    from scipy.spatial.transform import Rotation

    return Rotation.from_euler("xyz", np.asarray(angles_deg, np.float64), degrees=True).as_matrix()


def spec_placement(spec: dict, mesh) -> np.ndarray:
    """Start positions (Nu, 3) float64 [m] of the mesh's uv vertices from the specification's own
    panel translation and rotation. unsew's reader may have mirrored a clockwise panel's 2D
    coordinates (u -> -u); that is told by matching the panel's outline to the file's vertices."""
    scale = float(spec.get("properties", {}).get("units_in_meter", 100))
    x = np.zeros((len(mesh.uv), 3))
    for i, name in enumerate(mesh.panel_names):
        pd = spec["pattern"]["panels"][name]
        a, b = int(mesh.panel_offsets[i]), int(mesh.panel_offsets[i + 1])
        uv = np.asarray(mesh.uv[a:b], np.float64)
        V = np.asarray(pd["vertices"], np.float64) / scale
        bnd = uv[: int(mesh.n_boundary[i])]

        def miss(p, V=V):
            return float(np.linalg.norm(p[:, None] - V[None], axis=2).min(axis=0).max())

        if miss(bnd * [-1.0, 1.0]) < miss(bnd):
            uv = uv * [-1.0, 1.0]
        local = np.c_[uv, np.zeros(len(uv))]
        x[a:b] = (
            local @ spec_rotation(pd.get("rotation", [0, 0, 0])).T
            + np.asarray(pd.get("translation", [0, 0, 0]), np.float64) / scale
        )
    return x


def bend_around_body(x: np.ndarray, mesh, spec: dict, body_v: np.ndarray) -> np.ndarray:
    """The spec's placement with each front or back panel (its normal within 30 degrees of the
    Z axis) bent isometrically around the body's vertical axis at its own distance: a point at
    arc length ``s = x - cx`` across the panel goes to angle ``s / r`` on the circle of radius
    ``r = |z - cz|`` (cx, cz: the body's bounding-box centre). Heights, distances from the axis
    and lengths along the panel are kept; other panels (sleeves, side pieces) stay as placed.
    x: (Nu, 3) [m] -> (Nu, 3) [m]."""
    cx, cz = 0.5 * (body_v[:, 0].min() + body_v[:, 0].max()), 0.5 * (body_v[:, 2].min() + body_v[:, 2].max())
    out = x.copy()
    beside = beside_torso(x, mesh, body_v)
    for i, name in enumerate(mesh.panel_names):
        n = spec_rotation(spec["pattern"]["panels"][name].get("rotation", [0, 0, 0]))[:, 2]
        if abs(n[2]) < np.cos(np.radians(30.0)) or beside[i]:
            continue
        a, b = int(mesh.panel_offsets[i]), int(mesh.panel_offsets[i + 1])
        p = x[a:b]
        dz = p[:, 2] - cz
        r = np.maximum(np.abs(dz), 0.05)
        phi = (p[:, 0] - cx) / r
        out[a:b, 0] = cx + r * np.sin(phi)
        out[a:b, 2] = cz + np.sign(dz) * r * np.cos(phi)
    return out


def torso_sections(body_v: np.ndarray, band=0.015, gap=0.02, step=0.02):
    """The body's torso cross-sections: heights (R,) [m] and for each its half width and front and
    back z (R,) [m] each. At each height the body's vertices within ``band`` [m] are taken out
    from the axis (bounding-box centre x) to the first gap wider than ``gap`` across x (what lies
    beyond is an arm); below the crotch the section holds both legs."""
    cx = 0.5 * (body_v[:, 0].min() + body_v[:, 0].max())
    rows = []
    for y in np.arange(body_v[:, 1].min() + 0.05, body_v[:, 1].max(), step):
        sl = body_v[np.abs(body_v[:, 1] - y) < band]
        if len(sl) < 10:
            continue
        d = np.sort(np.abs(sl[:, 0] - cx))
        jumps = np.flatnonzero(np.diff(d) > gap)
        hw = d[jumps[0]] if len(jumps) else d[-1]
        t = sl[np.abs(sl[:, 0] - cx) <= hw + 1e-9]
        rows.append((y, hw, t[:, 2].max(), t[:, 2].min()))
    return tuple(np.array(c) for c in zip(*rows))


def beside_torso(x: np.ndarray, mesh, body_v: np.ndarray, gap=0.08) -> np.ndarray:
    """Per panel (P,) bool: a piece of a sleeve or cuff, which the specification places around the
    arm: its centre (the mean of its vertices x (Nu, 3) [m]) above the crotch and all of it to one
    side of the body's axis (bounding-box centre x), its nearest vertex more than ``gap`` [m] from
    it (a torso's, skirt's or waistband's panel reaches the centre front or back). Bent or wrapped
    around the torso's axis, such a piece is carried past the body's side to its far side (a
    sleeve's front half behind the arm)."""
    y0 = _crotch_height(body_v)
    cx = 0.5 * (body_v[:, 0].min() + body_v[:, 0].max())
    out = np.zeros(len(mesh.panel_names), bool)
    for i in range(len(mesh.panel_names)):
        p = x[int(mesh.panel_offsets[i]) : int(mesh.panel_offsets[i + 1])]
        side = np.sign(p[:, 0] - cx)
        near = np.abs(p[:, 0] - cx).min()
        out[i] = p[:, 1].mean() > y0 and abs(side.sum()) == len(p) and near > gap
    return out


def _crotch_height(body_v: np.ndarray, half=0.01) -> float:
    """The highest height [m] below the body's middle where no body vertex lies within ``half``
    [m] of its axis (between the legs)."""
    cx = 0.5 * (body_v[:, 0].min() + body_v[:, 0].max())
    mid = body_v[np.abs(body_v[:, 0] - cx) < half, 1]
    ys = np.arange(body_v[:, 1].min() + 0.1, 0.5 * (body_v[:, 1].min() + body_v[:, 1].max()), 0.01)
    empty = [y for y in ys if not np.any(np.abs(mid - y) < 0.01)]
    return float(max(empty)) if empty else float(ys[0])


def _ellipse_at(a: float, b: float, s: float, n=721) -> tuple[float, float]:
    """The point (x, z) at signed arc length ``s`` [m] from (0, b) on the ellipse x = a sin t,
    z = b cos t (a, b [m])."""
    t = np.linspace(-np.pi, np.pi, n)
    x, z = a * np.sin(t), b * np.cos(t)
    arc = np.r_[0.0, np.cumsum(np.hypot(np.diff(x), np.diff(z)))]
    arc -= np.interp(0.0, t, arc)
    return float(np.interp(s, arc, x)), float(np.interp(s, arc, z))


def wrap_on_torso(x: np.ndarray, mesh, spec: dict, body_v: np.ndarray, clearance=0.03, blend=0.1):
    """The start x (Nu, 3) [m] with each front or back panel (as :func:`bend_around_body` picks
    them) wrapped on the torso: a vertex at ``s = x - cx`` across its panel goes to arc length s
    from the front (back: the specification's side, :func:`_front_back`) centre of the ellipse of
    the torso's section at its height (half width and half depth plus ``clearance`` [m]); heights
    kept; the pieces :func:`beside_torso` finds are left as they are. Below the crotch the start is kept, and
    over ``blend`` [m] above it the two are mixed linearly, so legs stay as they are."""
    Y, HW, ZF, ZB = torso_sections(body_v)
    y0 = _crotch_height(body_v)
    cx = 0.5 * (body_v[:, 0].min() + body_v[:, 0].max())
    out = x.copy()
    beside = beside_torso(x, mesh, body_v)
    sides = _front_back(mesh, spec, body_v)
    for i, name in enumerate(mesh.panel_names):
        n = spec_rotation(spec["pattern"]["panels"][name].get("rotation", [0, 0, 0]))[:, 2]
        if abs(n[2]) < np.cos(np.radians(30.0)) or beside[i]:
            continue
        a_, b_ = int(mesh.panel_offsets[i]), int(mesh.panel_offsets[i + 1])
        side = float(sides[a_])
        for k in range(a_, b_):
            y = x[k, 1]
            w = float(np.clip((y - y0) / blend, 0.0, 1.0))
            if w == 0.0:
                continue
            zf, zb = np.interp(y, Y, ZF), np.interp(y, Y, ZB)
            px, pz = _ellipse_at(np.interp(y, Y, HW) + clearance, 0.5 * (zf - zb) + clearance, x[k, 0] - cx)
            wrapped = np.array([cx + px, y, 0.5 * (zf + zb) + side * pz])
            out[k] = w * wrapped + (1.0 - w) * x[k]
    return out


def clear_of_body(x: np.ndarray, mesh, body_v: np.ndarray, body_f: np.ndarray, step=0.01, reach=0.06):
    """The start x (Nu, 3) [m] with the vertices inside the body moved out horizontally, away
    from the body's vertical axis (its bounding-box centre), heights kept: each inside vertex by
    the multiple of ``step`` [m] that takes it out, plus one step; the vertices of its panel
    within ``reach`` [m] of it (rest 2D distance) by that push times (1 - distance / reach), so
    the panel bends out smoothly. Each vertex takes the largest push it is given; a vertex still
    inside after 30 steps is left there (inside: as checks.inside_mask tells it)."""
    import trimesh

    contains = trimesh.Trimesh(body_v, body_f, process=False).contains
    cx, cz = 0.5 * (body_v[:, 0].min() + body_v[:, 0].max()), 0.5 * (body_v[:, 2].min() + body_v[:, 2].max())
    d = x[:, [0, 2]] - [cx, cz]
    dirn = np.zeros_like(x)
    dirn[:, [0, 2]] = d / np.maximum(np.linalg.norm(d, axis=1, keepdims=True), 1e-9)
    push = np.zeros(len(x))
    inside = np.asarray(contains(x), bool)
    moved = inside.copy()
    for _ in range(30):
        if not inside.any():
            break
        push[inside] += step
        k = np.flatnonzero(inside)
        inside[k] = contains(x[k] + push[k, None] * dirn[k])
    push[moved] += step
    out = np.zeros(len(x))
    uv, pan = np.asarray(mesh.uv), np.asarray(mesh.uv_panel)
    for k in np.flatnonzero(moved):
        same = np.flatnonzero(pan == pan[k])
        w = np.clip(1.0 - np.linalg.norm(uv[same] - uv[k], axis=1) / reach, 0.0, 1.0)
        out[same] = np.maximum(out[same], push[k] * w)
    return x + out[:, None] * dirn


#: Edge labels that GarmentCode's programs put on the edges a garment hangs from (GarmentCodeData
#: holds them by attachment constraints): a lower garment's or waistband's top edge
#: (``lower_interface``, meta_garment.py) and a strapless bodice's top edge (``strapless_top``,
#: bodice.py). Their vertices are held at the height the specification puts them.
ATTACH_LABELS = ("lower_interface", "strapless_top")


def attached_uv(spec: dict, mesh) -> np.ndarray:
    """The uv vertices (k,) int64 of ``mesh`` on the specification's edges labelled ATTACH_LABELS."""
    idx = [
        np.asarray(v, np.int64)
        for (name, e), v in mesh.edge_verts.items()
        if spec["pattern"]["panels"][name]["edges"][e].get("label") in ATTACH_LABELS
    ]
    return np.unique(np.concatenate(idx)) if idx else np.zeros(0, np.int64)


def attachment(spec: dict, mesh, x0: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The uv vertices on the specification's edges labelled ATTACH_LABELS, (k,) int64, and their
    heights [m], (k,) float64: the mean start height (x0 (Nu, 3) [m], Y up) of the uv vertices
    sewn into the same vertex, so a seam's two sides are held at one height."""
    idx = attached_uv(spec, mesh)
    xu = np.asarray(mesh.x_of_u)
    ysum, cnt = np.zeros(int(mesh.n_x)), np.zeros(int(mesh.n_x))
    np.add.at(ysum, xu, x0[:, 1])
    np.add.at(cnt, xu, 1.0)
    return idx, (ysum / np.maximum(cnt, 1.0))[xu[idx]]


def _front_back(mesh, spec: dict, body_v: np.ndarray) -> np.ndarray:
    """Per uv vertex (Nu,) int: +1 on a front panel, -1 on a back panel (normal within 30 degrees
    of the Z axis, the side of the body's median z the specification places it on), 0 else. (The
    side is the specification's, not the bent start's: a panel wider than half the body's girth
    bent around it has most of its area past the body's sides.)"""
    x0 = spec_placement(spec, mesh)
    side = np.zeros(len(x0), np.int64)
    for i, name in enumerate(mesh.panel_names):
        n = spec_rotation(spec["pattern"]["panels"][name].get("rotation", [0, 0, 0]))[:, 2]
        if abs(n[2]) < np.cos(np.radians(30.0)):
            continue
        a, b = int(mesh.panel_offsets[i]), int(mesh.panel_offsets[i + 1])
        side[a:b] = 1 if np.mean(x0[a:b, 2]) > np.median(body_v[:, 2]) else -1
    return side


def over_body_guide(
    spec: dict, mesh, x0: np.ndarray, body_v: np.ndarray, body_f: np.ndarray, clearance=0.01, reach=0.1
):
    """Seams that must close over the top of the body (a shoulder seam between a front and a back
    panel): the stitched pairs joining a front to a back panel (:func:`_front_back`) whose midpoint
    in the start x0 (Nu, 3) [m] lies inside the body above the crotch, less than ``reach`` [m]
    below the body's top surface there (nothing of the body above that). Returns their uv vertices
    (k,) int64 and for each that top point plus ``clearance`` [m] up, (k, 3) float64 [m]: where
    the seam is sewn to."""
    import trimesh

    none = np.zeros(0, np.int64), np.zeros((0, 3))
    sp = np.asarray(mesh.seam_pairs, np.int64).reshape(-1, 2)
    side = _front_back(mesh, spec, body_v)
    sp = sp[side[sp[:, 0]] * side[sp[:, 1]] < 0]
    mid = 0.5 * (x0[sp[:, 0]] + x0[sp[:, 1]])
    tm = trimesh.Trimesh(body_v, body_f, process=False)
    if len(sp):
        keep = (mid[:, 1] > _crotch_height(body_v)) & np.asarray(tm.contains(mid), bool)
        sp, mid = sp[keep], mid[keep]
    if not len(sp):
        return none
    up = np.tile([0.0, 1.0, 0.0], (len(mid), 1))
    hit, ray, _ = tm.ray.intersects_location(mid, up, multiple_hits=False)
    top = np.full_like(mid, np.inf)
    top[ray] = hit
    near = top[:, 1] - mid[:, 1] < reach
    above = np.zeros(len(mid), bool)
    if near.any():
        _, r2, _ = tm.ray.intersects_location(top[near] + [0.0, 1e-4, 0.0], up[near], multiple_hits=False)
        above[np.flatnonzero(near)[r2]] = True
    keep = near & ~above
    top = top[keep] + [0.0, clearance, 0.0]
    return sp[keep].T.ravel(), np.r_[top, top]


#: newton's settings for starts from the specification (flat panels up to half a metre apart):
#: the foreign benchmark's, with the sewing force and speed capped and four times the sewing frames.
SEW_FROM_SPEC = {
    "seam_force_max_n": 1.0,
    "sew_speed_max_m_s": 0.5,
    "sew_frames": 120,
    "hold_frames": 135,
    "soft_contact_ke": 1.0e4,
}


def mesh_spec(spec: dict, name: str, edge_length: float):
    """unsew's panel mesh of a specification (the benchmark's simulators need one)."""
    from unsew.io.garmentcode import pattern_from_dict
    from unsew.meshing.sew import mesh_pattern

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        pattern = pattern_from_dict(json.loads(json.dumps(spec)), name=name)
    return mesh_pattern(pattern, edge_length=edge_length)


def write_obj(path: Path, v: np.ndarray, f: np.ndarray, header: str) -> None:
    with open(path, "w") as fh:
        fh.write(f"# {header}\n")
        fh.write("".join(f"v {a:.5f} {b:.5f} {c:.5f}\n" for a, b, c in v))
        fh.write("".join(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in f))


#: ... and while seams are guided over the body (:func:`over_body_guide`): the body without
#: friction while sewing, so that the pulled cloth slides over the shoulder instead of sticking.
GUIDED_SEWING = {"sew_contact_mu": 0.0}


def _newton_drape(mesh, x0, body_v, body_f, lower, attach=None, guide=None):
    """newton's drape (benchmarks/foreign/newton_drape.py) with its retry settings; ``attach``:
    (uv indices, heights [m]) held at those heights (see :func:`attachment`); ``guide``: (uv
    indices, points [m]) pulled to those points while sewing (see :func:`over_body_guide`)."""
    sys.path.insert(0, str(HERE.parent / "foreign"))
    import newton_drape

    for k, extra in enumerate(newton_drape.FALLBACKS):
        guided = GUIDED_SEWING if guide is not None and len(guide[0]) else {}
        settings = {**newton_drape.SETTINGS, **SEW_FROM_SPEC, **guided, **extra}
        try:
            x, info = newton_drape.drape_newton(
                mesh,
                x0,
                body_v,
                body_f,
                lower=lower,
                settings=settings,
                log=_log,
                holds={"attach": attach, "guide": guide},
            )
            return x, info, settings
        except RuntimeError as exc:
            _log(f"  {exc}")
            if k + 1 == len(newton_drape.FALLBACKS):
                raise


def newton_start(spec: dict, mesh, x_spec: np.ndarray, body_v: np.ndarray, body_f: np.ndarray) -> np.ndarray:
    """The start newton dresses a specification from, (Nu, 3) [m]: its own placement ``x_spec``
    bent around the body, front and back wrapped on the torso, cleared of the body."""
    x0 = bend_around_body(x_spec, mesh, spec, body_v)
    return clear_of_body(wrap_on_torso(x0, mesh, spec, body_v), mesh, body_v, body_f)


def newton_dress(spec: dict, mesh, x0: np.ndarray, body, lower_type: bool):
    """newton's drape of a specification from the start ``x0`` (Nu, 3) [m] on ``body`` (verts,
    faces), the targets' recipe: labelled edges held (:func:`attachment`; a lower garment
    without any held by its waist instead), seams over the body's top guided. Returns (x, info,
    settings, (held vertices, guided vertices))."""
    body_v, body_f = body
    att = attachment(spec, mesh, x0)
    guide = over_body_guide(spec, mesh, x0, body_v, body_f)
    x, info, settings = _newton_drape(mesh, x0, body_v, body_f, lower_type and not len(att[0]), att, guide)
    return x, info, settings, (len(att[0]), len(guide[0]))


def build_case(
    cid: str, seed: int, index: int, out: Path, *, drape: bool = True, count: int | None = None
) -> dict:
    """Build one case folder ``out/cid``; returns its status record. ``drape=False``: everything
    but the newton drape (no target.obj), for a quick check of sampling, sizing and placement."""
    sys.path.insert(0, str(HERE.parent / "foreign"))
    import checks

    m = manifest()
    t0 = time.time()
    src = _sampled_design(cid, seed, out, count)
    rec = {"case": cid, "seed": seed, "body": src.entry["body"]["name"], "type": src.truth["type"]}
    body_v, body_f = read_body(src.body_dir)
    d = out / cid
    try:
        mesh = mesh_spec(src.spec, cid, m["edge_length_m"])
    except Exception as exc:  # noqa: BLE001 - unsew cannot mesh this design: recorded, counted
        rec.update(status="failed", reason=f"meshing: {type(exc).__name__}: {str(exc).splitlines()[0][:160]}")
        if not (d / "target.obj").is_file():
            src.write(d)
        return rec
    x_spec = spec_placement(src.spec, mesh)
    x0 = newton_start(src.spec, mesh, x_spec, body_v, body_f)
    rec["spec_inside_fraction"] = round(float(checks.inside_mask(x_spec, body_v, body_f).mean()), 4)
    rec["start_inside_fraction"] = round(float(checks.inside_mask(x0, body_v, body_f).mean()), 4)
    rec["vertices"] = int(mesh.n_x)
    rec["arm_pieces"], rec["panels_bent_past_side"] = _start_counts(x_spec, mesh, src.spec, body_v)
    _log(
        f"{cid}: {src.truth['type']}, {src.truth['panels']} panels, {mesh.n_x} vertices, "
        f"{rec['spec_inside_fraction']:.1%} of the spec's placement and "
        f"{rec['start_inside_fraction']:.1%} of the bent start inside the body"
    )
    if not drape:
        if not (d / "target.obj").is_file():
            src.write(d)
        rec.update(status="placed", seconds=round(time.time() - t0, 1))
        return rec
    try:
        x, info, settings, held = newton_dress(
            src.spec, mesh, x0, (body_v, body_f), src.truth["type"] in LOWER_TYPES
        )
        rec["attached_vertices"], rec["guided_vertices"] = held
    except RuntimeError as exc:
        rec.update(status="failed", reason=f"newton: {exc}", seconds=round(time.time() - t0, 1))
        return rec
    fails = _accept(rec, x, x0, mesh, (body_v, body_f), info)
    _write_built(out, src, x, mesh, (body_v, body_f), rec, fails, (info, settings))
    rec.update(status="built" if not fails else "failed", seconds=round(time.time() - t0, 1))
    if fails:
        rec["reason"] = "; ".join(fails)
    _log(f"{cid}: {rec['status']} in {rec['seconds']:.0f} s" + (f" ({rec['reason']})" if fails else ""))
    return rec


def _start_counts(x_spec: np.ndarray, mesh, spec: dict, body_v: np.ndarray) -> tuple[int, int]:
    """(panels :func:`beside_torso` keeps as placed, front or back panels whose bend around the
    body leaves most of them on the other side of it): designs with neither start as they did
    before either rule (docs/decisions/032). x_spec: (Nu, 3) [m], the specification's placement."""
    side = _front_back(mesh, spec, body_v)
    bent = bend_around_body(x_spec, mesh, spec, body_v)
    med = np.median(body_v[:, 2])
    past = 0
    for i in range(len(mesh.panel_names)):
        a, b = int(mesh.panel_offsets[i]), int(mesh.panel_offsets[i + 1])
        past += int(side[a] != 0 and side[a] * (np.mean(bent[a:b, 2]) - med) < 0)
    fb = side[np.asarray(mesh.panel_offsets[:-1], np.int64)] != 0
    return int((beside_torso(x_spec, mesh, body_v) & fb).sum()), past


class _Design:
    """One sampled design: its id and seed, the seed's manifest entry, its body folder, its
    specification, design_params.yaml's text and the truth read from it."""

    def __init__(self, cid, seed, entry, body_dir, spec, design_text, truth):
        self.cid, self.seed, self.entry, self.body_dir = cid, seed, entry, body_dir
        self.spec, self.design_text, self.truth = spec, design_text, truth

    def write(self, d: Path) -> None:
        write_design_files(
            d, self.body_dir, self.spec, self.design_text, self.truth, self.entry, self.cid, self.seed
        )


def _sampled_design(cid: str, seed: int, out: Path, count: int | None) -> _Design:
    """Seed ``seed``'s body made and its designs sampled (each once); design ``cid`` and its truth."""
    from truth import built_choices, truth_of_design

    m = manifest()
    entry = seed_entry(seed)
    body_dir = make_body(entry, out)
    ddir = sample_seed(seed, m["count"] if count is None else count, body_dir, out) / cid
    spec = json.loads((ddir / f"{cid}_specification.json").read_text())
    design_text = (ddir / "design_params.yaml").read_text()
    truth = truth_of_design(design_text)
    truth["panels"] = len(spec["pattern"]["panels"])
    truth["design_choices"] = truth["choices"]
    truth["choices"] = built_choices(truth["choices"], spec)
    return _Design(cid, seed, entry, body_dir, spec, design_text, truth)


def top_drop(x: np.ndarray, x0: np.ndarray, mesh) -> float:
    """How far [m] the garment's top came down from its start: x (n_x, 3) drape, x0 (n_uv, 3)
    start. A hood's panels are left out (where any other panel remains): a hood's peak settles
    onto the head by itself, while a garment that slid down brings its shoulders with it."""
    keep = np.array(["hood" not in mesh.panel_names[p] for p in mesh.uv_panel])
    if not keep.any():
        keep[:] = True
    return float(x0[keep, 1].max() - x[mesh.x_of_u[keep], 1].max())


def wrap_share(
    x: np.ndarray, faces: np.ndarray, body_v: np.ndarray, *, bins: int = 36, slice_m: float = 0.10
) -> float:
    """The largest share of ``bins`` directions round the body's vertical axis (the mean x, z of
    its vertices) that the garment's surface (20,000 area-uniform samples) covers within one
    ``slice_m`` high slice. x (n, 3), faces (F, 3), body_v (m, 3) [m], Y up."""
    import trimesh

    x = trimesh.sample.sample_surface(trimesh.Trimesh(x, faces, process=False), 20000, seed=0)[0]
    axis = body_v[:, [0, 2]].mean(axis=0)
    ang = np.arctan2(x[:, 0] - axis[0], x[:, 2] - axis[1])
    b = np.minimum(((ang + np.pi) / (2 * np.pi) * bins).astype(int), bins - 1)
    level = np.floor(x[:, 1] / slice_m).astype(int)
    best = 0
    for lv in np.unique(level):
        best = max(best, len(np.unique(b[level == lv])))
    return best / bins


def overstretched(st: np.ndarray, mesh) -> float:
    """The share of ``mesh``'s rest area (its uv triangles) whose stretch ``st`` (F,) (largest
    principal stretch - 1 per triangle) exceeds MAX_STRETCH."""
    from unsew.meshing.triangulate import signed_areas

    area = np.abs(signed_areas(np.asarray(mesh.uv, np.float64), np.asarray(mesh.faces_uv)))
    return float(area[st > MAX_STRETCH].sum() / area.sum())


def _stretch_checks(rec: dict, x: np.ndarray, mesh) -> list[str]:
    """The stretch check of drape ``x`` (n_x, 3) [m] on ``mesh`` recorded into ``rec``; its failed line."""
    import checks

    st = checks.stretch(x, np.asarray(mesh.faces), np.asarray(mesh.uv), np.asarray(mesh.faces_uv))
    share = overstretched(st, mesh)
    rec.update(
        stretch_p95=round(float(np.percentile(st, 95)), 4),
        stretch_max=round(float(st.max()), 3),
        overstretched_share=round(share, 5),
    )
    if share <= MAX_OVERSTRETCHED:
        return []
    return [
        f"{share:.2%} of the cloth stretched past {1 + MAX_STRETCH:g}x (largest {1 + float(st.max()):.2f}x)"
    ]


def inside_share(x: np.ndarray, body_v: np.ndarray, body_f: np.ndarray) -> float:
    """The share of the drape's vertices x (n, 3) [m] inside the body, those lying under a sole
    (less than UNDERFOOT above the body's lowest point) left out."""
    import checks

    inside = np.asarray(checks.inside_mask(x, body_v, body_f), bool)
    return float((inside & (x[:, 1] > body_v[:, 1].min() + UNDERFOOT)).mean())


def _accept(rec: dict, x: np.ndarray, x0: np.ndarray, mesh, body, info: dict) -> list[str]:
    """The drape's acceptance checks (inside, stretch, floor, slide, wrap) recorded into ``rec``;
    returns the failed ones' lines (empty: accepted). x (n_x, 3), x0 (n_uv, 3) [m]: drape, start."""
    body_v, body_f = body
    inside = inside_share(x, body_v, body_f)
    fails = []
    if inside >= MAX_INSIDE:
        fails.append(f"{inside:.2%} of vertices inside the body")
    fails += _stretch_checks(rec, x, mesh)
    if x[:, 1].min() < body_v[:, 1].min() - GROUND_TOL:
        fails.append("through the ground")
    drop = top_drop(x, x0, mesh)
    if drop > MAX_DROP:
        fails.append(f"slid down {drop * 100:.0f} cm from where the specification puts its top")
    wrap = wrap_share(x, np.asarray(mesh.faces), body_v)
    if wrap < MIN_WRAP:
        fails.append(f"off the body: it covers {wrap:.0%} of the directions round the body at best")
    if rec["case"] in REFUSED_ON_SIGHT:
        fails.append(REFUSED_ON_SIGHT[rec["case"]])
    rec.update(
        inside_fraction=round(inside, 5),
        top_drop_m=round(drop, 3),
        wrap_share=round(wrap, 3),
        seam_gap_after_sewing_mm=round(info["gap_after_sewing_m"] * 1000, 1),
        drape_s=round(info["sew_s"] + info["drape_s"], 1),
    )
    return fails


def _write_built(out: Path, src: _Design, x, mesh, body, rec: dict, fails: list[str], run) -> None:
    """Write the draped case folder ``out/cid`` (through a temporary folder): the design's files,
    target.obj, preview.png and meta.json with the simulator's settings and the checks."""
    import checks
    import newton
    import warp

    info, settings = run
    cid, faces = src.cid, np.asarray(mesh.faces)
    tmp = out / f".{cid}.tmp"
    shutil.rmtree(tmp, ignore_errors=True)
    src.write(tmp)
    verdict = "ok" if not fails else "FAIL: " + "; ".join(fails)
    title = f"{cid} {src.truth['type']}  inside {rec['inside_fraction']:.2%}  {verdict}"
    checks.preview(tmp / "preview.png", x, faces, *body, title=title)
    header = f"GarmentCode design {cid} draped by newton {newton.__version__} SolverStyle3D"
    write_obj(tmp / "target.obj", x, faces, header)
    meta = json.loads((tmp / "meta.json").read_text())
    check_keys = ("inside_fraction", "stretch_p95", "stretch_max", "seam_gap_after_sewing_mm", "top_drop_m")
    meta |= {
        "simulator": {
            "name": "newton SolverStyle3D (CPU)",
            "newton": newton.__version__,
            "warp": warp.__version__,
            "start": "the specification's panel translation and rotation, front and back panels bent "
            "around the body's axis (build.bend_around_body), vertices inside the body moved out "
            "(build.clear_of_body)",
            "attached": f"{rec.get('attached_vertices', 0)} vertices on edges labelled "
            f"{' or '.join(ATTACH_LABELS)} held at the specification's height (build.attachment)",
            "settings": {k: (None if v == float("inf") else v) for k, v in settings.items()},
            "mesh_edge_length_m": manifest()["edge_length_m"],
            "frames": info["frames"],
        },
        "checks": {k: rec[k] for k in check_keys},
    }
    (tmp / "meta.json").write_text(json.dumps(meta, indent=1))
    shutil.rmtree(out / cid, ignore_errors=True)
    tmp.rename(out / cid)


def write_design_files(
    d: Path, body_dir: Path, spec: dict, design_text: str, truth: dict, entry: dict, cid: str, seed: int
) -> None:
    """Write a case folder's files that need no drape: body.obj (+ skeleton.json), pattern_gt.json,
    design_params.yaml, truth.json and meta.json (frame and source only)."""
    d.mkdir(parents=True, exist_ok=True)
    shutil.copyfile(body_dir / "body.obj", d / "body.obj")
    if (body_dir / "skeleton.json").is_file():
        shutil.copyfile(body_dir / "skeleton.json", d / "skeleton.json")
    (d / "pattern_gt.json").write_text(json.dumps(spec, indent=1))
    (d / "design_params.yaml").write_text(design_text)
    (d / "truth.json").write_text(json.dumps(truth, indent=1))
    meta = {
        "units": "m",
        "up": "y",
        "front": "z",
        "source": {
            "design": cid,
            "seed": seed,
            "sampler": "shared/garmentcode/sample_designs.py (GarmentCode, MIT)",
            "body": entry["body"],
        },
    }
    (d / "meta.json").write_text(json.dumps(meta, indent=1))


def recheck(out: Path, cid: str) -> dict | None:
    """Re-run the acceptance checks on a written case (its target against the specification's
    start) and update its status record; None where the case has no target."""
    sys.path.insert(0, str(HERE.parent / "foreign"))
    import checks

    d, st = out / cid, out / "_status" / f"{cid}.json"
    if not (d / "target.obj").is_file() or not st.is_file():
        return None
    rec = json.loads(st.read_text())
    spec = json.loads((d / "pattern_gt.json").read_text())
    body_v, body_f = read_body(d)
    mesh = mesh_spec(spec, cid, manifest()["edge_length_m"])
    x0 = bend_around_body(spec_placement(spec, mesh), mesh, spec, body_v)
    x0 = clear_of_body(wrap_on_torso(x0, mesh, spec, body_v), mesh, body_v, body_f)
    import trimesh

    x = np.asarray(trimesh.load(d / "target.obj", process=False, force="mesh").vertices)
    inside = inside_share(x, body_v, body_f)
    drop = top_drop(x, x0, mesh)
    redo = ("inside the body", "slid down", "off the body", "on sight")
    same_mesh = len(x) == mesh.n_x  # a kept target on an earlier mesh keeps its recorded stretch
    if same_mesh:
        redo += ("stretch",)
    fails = [f for f in (rec.get("reason") or "").split("; ") if f and not any(r in f for r in redo)]
    if same_mesh:
        fails += _stretch_checks(rec, x, mesh)
    if inside >= MAX_INSIDE:
        fails.append(f"{inside:.2%} of vertices inside the body")
    if drop > MAX_DROP:
        fails.append(f"slid down {drop * 100:.0f} cm from where the specification puts its top")
    wrap = wrap_share(x, np.asarray(mesh.faces), body_v)
    if wrap < MIN_WRAP:
        fails.append(f"off the body: it covers {wrap:.0%} of the directions round the body at best")
    if cid in REFUSED_ON_SIGHT:
        fails.append(REFUSED_ON_SIGHT[cid])
    rec.update(
        inside_fraction=round(inside, 5),
        top_drop_m=round(drop, 3),
        wrap_share=round(wrap, 3),
        status="failed" if fails else "built",
    )
    rec.pop("reason", None)
    if fails:
        rec["reason"] = "; ".join(fails)
    verdict = "ok" if not fails else "FAIL: " + "; ".join(fails)
    title = f"{cid} {rec.get('type', '')}  inside {inside:.2%}  {verdict}"
    checks.preview(d / "preview.png", x, np.asarray(mesh.faces), body_v, body_f, title=title)
    return rec


def record(out: Path, rec: dict) -> None:
    """Put one case's status into ``out/_status/<case>.json`` and rebuild ``out/build.json`` from
    all of them (in manifest order), so that several builds may run side by side."""
    st = out / "_status"
    st.mkdir(parents=True, exist_ok=True)
    (st / f"{rec['case']}.json").write_text(json.dumps(rec, indent=1))
    allr = {p.stem: json.loads(p.read_text()) for p in st.glob("*.json")}
    order = [c for c, _, _ in case_ids()]
    allr = {k: allr[k] for k in sorted(allr, key=lambda c: order.index(c) if c in order else len(order))}
    tmp = out / f".build.{os.getpid()}.json"
    tmp.write_text(json.dumps(allr, indent=1))
    tmp.replace(out / "build.json")
