"""Sewing-pattern designs for the foreign benchmark, written as GarmentCode specification JSON.

Independent of unsew's base generators (src/unsew/pattern/base/): each design is drafted here
from a body's measurements the way a pattern maker drafts a block (quarter girths plus ease,
darts taking the waist-hip difference, a sleeve cap matched to the armhole), and then left
alone: the benchmark drapes it on that body with another simulator and asks unsew to recover it.

Frame of every panel: x across, y up, y = 0 at the hem, outline counter-clockwise seen from
outside the garment. Front panels are placed at +z with no rotation, back panels at -z turned
180 deg about y (so a back panel's +x is the body's right), sleeves along their arm. Lengths here
are metres; the JSON is written in cm (``units_in_meter`` 100) with relative curvature.

``DESIGNS`` maps a design name to a function ``(measurements: dict, skeleton: dict) -> dict``
(the specification). ``measurements`` are :func:`unsew.body.measure.measure_body`'s metres;
``skeleton`` maps joint names to positions (3,) [m].
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from unsew.pattern.curves import absolute_to_relative
from unsew.pattern.model import matrix_to_euler_xyz

ROT_BACK = [0.0, 180.0, 0.0]
#: z of the placement hints of front / back panels [m] (placement only reads the side).
Z_HINT = 0.15


class Spec:
    """A pattern being drafted: panels (named edges) and stitches."""

    def __init__(self, name: str):
        self.name = name
        self.panels: dict = {}
        self.names: dict = {}  # panel -> {edge name: index}
        self.stitches: list = []

    def panel(self, name, pts, edges, *, translation, rotation=(0.0, 0.0, 0.0), label=None):
        """pts: (n, 2) [m] counter-clockwise; edges: list of n (edge name, curve) where edge i
        runs pts[i] -> pts[i+1]; curve None, ("q", [(x, y)]) or ("c", [(x, y), (x, y)]) with
        absolute control points [m], or ("arc", radius, large, right)."""
        pts = np.asarray(pts, float)
        assert _area(pts) > 0, f"{name} is not counter-clockwise"
        out_edges, names = [], {}
        for i, (ename, curve) in enumerate(edges):
            a, b = pts[i], pts[(i + 1) % len(pts)]
            e = {"endpoints": [i, (i + 1) % len(pts)]}
            if curve is not None and curve[0] in ("q", "c"):
                rel = absolute_to_relative(a, b, np.asarray(curve[1], float)).reshape(-1, 2)
                e["curvature"] = {
                    "type": "quadratic" if curve[0] == "q" else "cubic",
                    "params": rel.round(6).tolist(),
                }
            elif curve is not None and curve[0] == "arc":
                e["curvature"] = {
                    "type": "circle",
                    "params": [round(curve[1] * 100, 4), int(curve[2]), int(curve[3])],
                }
            if ename:
                names[ename] = i
            out_edges.append(e)
        self.panels[name] = {
            "translation": [round(float(t) * 100, 4) for t in translation],
            "rotation": [float(r) for r in rotation],
            "vertices": (pts * 100).round(4).tolist(),
            "edges": out_edges,
        }
        if label:
            self.panels[name]["label"] = label
        self.names[name] = names

    def mirrored(self, src: str, name: str, *, translation, rotation):
        """Add the mirror image (x -> -x) of panel ``src``: edge names follow their edges."""
        p = self.panels[src]
        v = np.asarray(p["vertices"], float) / 100
        n = len(v)
        idx = [(n - k) % n for k in range(n)]
        w = v[idx] * np.array([-1.0, 1.0])
        edges = []
        for k in range(n):
            e0 = p["edges"][n - 1 - k]  # original edge n-1-k, reversed and mirrored
            e = {"endpoints": [k, (k + 1) % n]}
            c = e0.get("curvature")
            if c is not None:
                if c["type"] == "circle":
                    e["curvature"] = dict(c)
                else:
                    e["curvature"] = {
                        "type": c["type"],
                        "params": [[round(1 - s, 6), t] for s, t in c["params"][::-1]],
                    }
            edges.append(e)
        self.panels[name] = {
            "translation": [round(float(t) * 100, 4) for t in translation],
            "rotation": [float(r) for r in rotation],
            "vertices": (w * 100).round(4).tolist(),
            "edges": edges,
        }
        self.names[name] = {en: n - 1 - i for en, i in self.names[src].items()}

    def stitch(self, pa, ea, pb, eb):
        self.stitches.append(
            [{"panel": pa, "edge": self.names[pa][ea]}, {"panel": pb, "edge": self.names[pb][eb]}]
        )

    def edge_len(self, panel, ename) -> float:
        p = self.panels[panel]
        i = self.names[panel][ename]
        a, b = (np.asarray(p["vertices"][j], float) / 100 for j in p["edges"][i]["endpoints"])
        return float(np.linalg.norm(b - a))

    def to_dict(self) -> dict:
        return {
            "pattern": {"panels": self.panels, "stitches": self.stitches, "panel_order": sorted(self.panels)},
            "properties": {
                "curvature_coords": "relative",
                "normalize_panel_translation": False,
                "units_in_meter": 100,
            },
            "parameters": {"design": self.name, "author": "benchmarks/foreign/designs.py"},
        }


def _area(p):
    x, y = p[:, 0], p[:, 1]
    return 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))


# -- lower garments: waist edges, darts, waistbands ---------------------------------------------


def _waist_with_darts(centres, top_y, dart_w, dart_len):
    """Points of a waist line running right to left at height ``top_y`` with a dart ``dart_w``
    wide and ``dart_len`` long at each x in ``centres`` (decreasing), between its two corners;
    returns (points, edge names) for the edges from the first corner to the last."""
    if not centres:
        return [], [("waist0", None)]
    pts, names = [], []
    k = 0
    for c in centres:
        names.append((f"waist{k}", None))
        pts += [(c + dart_w / 2, top_y), (c, top_y - dart_len), (c - dart_w / 2, top_y)]
        names += [(f"dart{k}a", None), (f"dart{k}b", None)]
        k += 1
    names.append((f"waist{k}", None))
    return pts, names


def _waist_edges(spec, panel):
    return sorted((e for e in spec.names[panel] if e.startswith("waist")), key=lambda s: int(s[5:]))


def _edge_x(spec, panel, ename) -> float:
    p = spec.panels[panel]
    return float(np.mean([p["vertices"][j][0] for j in p["edges"][spec.names[panel][ename]]["endpoints"]]))


def _sew_darts(spec, panel):
    for e in list(spec.names[panel]):
        if e.startswith("dart") and e.endswith("a"):
            spec.stitch(panel, e, panel, e[:-1] + "b")


def _waistband(spec, side, panels, y0, height):
    """A straight band over the waist edges of ``panels`` (ordered by increasing panel x, all of
    the same side), sewn to them edge by edge; returns its name."""
    segs = []
    for p in panels:  # each panel's waist edges from its smallest x to its largest
        segs += sorted(
            ((p, e, spec.edge_len(p, e)) for e in _waist_edges(spec, p)),
            key=lambda t: _edge_x(spec, t[0], t[1]),
        )
    total = sum(s[2] for s in segs)
    xs = -total / 2 + np.concatenate([[0.0], np.cumsum([s[2] for s in segs])])
    pts = [(x, 0.0) for x in xs] + [(xs[-1], height), (xs[0], height)]
    edges = [(f"b{i}", None) for i in range(len(segs))] + [("side_r", None), ("top", None), ("side_l", None)]
    name = f"waistband_{side}"
    spec.panel(
        name,
        pts,
        edges,
        translation=(0, y0, Z_HINT if side == "front" else -Z_HINT),
        rotation=(0, 0, 0) if side == "front" else ROT_BACK,
    )
    for i, (p, e, _) in enumerate(segs):
        spec.stitch(name, f"b{i}", p, e)
    return name


def skirt(m, J, *, length, flare, darts=2, waistband=True, slit=False, name="skirt"):
    """Two-panel skirt (front, back), side seams, ``flare`` [m] added to each quarter hem,
    optional darts and waistband. ``length``: waist to hem [m]."""
    spec = Spec(name)
    band = 0.04 if waistband else 0.0
    top = m["waist_height"] - 0.02  # skirt top (band centred on the waist)
    hem_y = top - length
    L = top - hem_y
    hq = (m["hip"] + 0.05) / 4
    wq = (m["waist"] + 0.03) / 4
    dart_w = min(0.025, max(0.0, (hq - wq) * 0.6 / 2)) if darts else 0.0
    wtop = wq + darts * dart_w / 2 * (1 if darts else 0)
    yh = max(L - 0.18, L * 0.4)
    hh = hq + flare
    for side in ("front", "back"):
        dl = 0.09 if side == "front" else 0.12
        wp, wn = _waist_with_darts([0.45 * wtop, -0.45 * wtop][:darts], L, dart_w, dl)
        pts = [(-hh, 0), (hh, 0), (hq, yh), (wtop, L)] + wp + [(-wtop, L), (-hq, yh)]
        hem = ("q", [(0, -0.35 * flare)]) if flare > 0.02 else None
        edges = [
            ("hem", hem),
            ("side_r_lo", None),
            ("side_r_hi", ("q", [(0.5 * (hq + wtop) + 0.012, 0.5 * (yh + L))])),
        ]
        edges += wn + [
            ("side_l_hi", ("q", [(-0.5 * (hq + wtop) - 0.012, 0.5 * (yh + L))])),
            ("side_l_lo", None),
        ]
        spec.panel(
            f"skirt_{side}",
            pts,
            edges,
            translation=(0, hem_y, Z_HINT if side == "front" else -Z_HINT),
            rotation=(0, 0, 0) if side == "front" else ROT_BACK,
        )
        _sew_darts(spec, f"skirt_{side}")
    for a, b in (("skirt_front", "skirt_back"), ("skirt_back", "skirt_front")):
        spec.stitch(a, "side_r_lo", b, "side_l_lo")
        spec.stitch(a, "side_r_hi", b, "side_l_hi")
    if waistband:
        for side in ("front", "back"):
            _waistband(spec, side, [f"skirt_{side}"], top, band)
        spec.stitch("waistband_front", "side_r", "waistband_back", "side_l")
        spec.stitch("waistband_back", "side_r", "waistband_front", "side_l")
    return spec.to_dict()


def circle_skirt(m, J, *, length, waistband=True, name="circle_skirt"):
    """Half-circle skirt: two quarter-circle sectors (front, back) whose waist arcs make the
    waist girth plus ease; optional waistband."""
    spec = Spec(name)
    top = m["waist_height"] - 0.02
    W = m["waist"] + 0.03
    rw = W / math.pi  # two 90-degree sectors: 2 * (pi/2) * rw = W
    rh = rw + length
    c45 = math.cos(math.pi / 4)
    # sector centred above: centre (0, rh); hem lowest point at y = 0
    p0 = (-rh * c45, rh - rh * c45)
    p1 = (rh * c45, rh - rh * c45)
    p2 = (rw * c45, rh - rw * c45)
    p3 = (-rw * c45, rh - rw * c45)
    yc = rh - rw * c45
    for side in ("front", "back"):
        edges = [
            ("hem", ("arc", rh, 0, 1)),
            ("side_r", None),
            ("waist0", ("arc", rw, 0, 0)),
            ("side_l", None),
        ]
        spec.panel(
            f"skirt_{side}",
            [p0, p1, p2, p3],
            edges,
            translation=(0, top - yc, Z_HINT if side == "front" else -Z_HINT),
            rotation=(0, 0, 0) if side == "front" else ROT_BACK,
        )
    spec.stitch("skirt_front", "side_r", "skirt_back", "side_l")
    spec.stitch("skirt_back", "side_r", "skirt_front", "side_l")
    if waistband:
        # the band is straight: sew it to the arc of equal length
        for side in ("front", "back"):
            arc = rw * math.pi / 2
            pts = [(-arc / 2, 0), (arc / 2, 0), (arc / 2, 0.04), (-arc / 2, 0.04)]
            name_b = f"waistband_{side}"
            spec.panel(
                name_b,
                pts,
                [("b0", None), ("side_r", None), ("top", None), ("side_l", None)],
                translation=(0, top, Z_HINT if side == "front" else -Z_HINT),
                rotation=(0, 0, 0) if side == "front" else ROT_BACK,
            )
            spec.stitch(name_b, "b0", f"skirt_{side}", "waist0")
        spec.stitch("waistband_front", "side_r", "waistband_back", "side_l")
        spec.stitch("waistband_back", "side_r", "waistband_front", "side_l")
    return spec.to_dict()


def trousers(m, J, *, hem_y, hem_girth, darts=1, waistband=True, name="trousers"):
    """Four leg panels (front/back, left/right), crotch curves, in- and outseams, optional
    darts and waistband. ``hem_y``: hem height above the floor [m]; ``hem_girth``: per leg [m]."""
    spec = Spec(name)
    top = m["waist_height"] - 0.02
    crotch = m["crotch_height"] - 0.025
    hip_y = 0.5 * (m["waist_height"] + m["crotch_height"]) - 0.03
    yw, yc, yh = top - hem_y, crotch - hem_y, hip_y - hem_y
    hq = (m["hip"] + 0.07) / 4
    wq = (m["waist"] + 0.04) / 4
    for side, ext, dz in (("front", m["hip"] / 16, Z_HINT), ("back", m["hip"] / 9, -Z_HINT)):
        dart_w = min(0.02, max(0.0, hq - wq - 0.015)) if darts else 0.0
        wtop = wq + darts * dart_w
        cen = (hq - ext) / 2  # leg centre line
        hh = hem_girth / 4
        pts = [(cen - hh, 0), (cen + hh, 0), (hq, yh)]
        # waist from the side (wtop) to the centre (0): the waist edges
        wp, wn = _waist_with_darts(
            [0.5 * wtop] if darts else [], yw, dart_w, 0.08 if side == "front" else 0.11
        )
        pts += [(wtop, yw)] + wp + [(0.0, yw), (-ext, yc)]
        # crotch curve: straight down the centre then out to the crotch point
        crotch_curve = ("q", [(0.0, yc + 0.01)])
        edges = [
            ("hem", None),
            ("out_lo", None),
            ("out_hi", ("q", [(0.5 * (hq + wtop) + 0.01, 0.5 * (yh + yw))])),
        ]
        edges += wn + [("crotch", crotch_curve), ("inseam", None)]
        spec.panel(
            f"{side}_l",
            pts,
            edges,
            translation=(0.1, hem_y, dz),
            rotation=(0, 0, 0) if side == "front" else ROT_BACK,
        )
    # front left as drafted (outseam at +x = body's left); back right as drafted (its +x is the
    # body's right when turned); their mirror images are the other two
    spec.panels["back_r"] = spec.panels.pop("back_l")
    spec.names["back_r"] = spec.names.pop("back_l")
    spec.panels["back_r"]["translation"][0] = -10.0
    spec.mirrored("front_l", "front_r", translation=(-0.1, hem_y, Z_HINT), rotation=(0, 0, 0))
    spec.mirrored("back_r", "back_l", translation=(0.1, hem_y, -Z_HINT), rotation=ROT_BACK)
    for p in ("front_l", "front_r", "back_l", "back_r"):
        _sew_darts(spec, p)
    for s in ("l", "r"):
        spec.stitch(f"front_{s}", "out_lo", f"back_{s}", "out_lo")
        spec.stitch(f"front_{s}", "out_hi", f"back_{s}", "out_hi")
        spec.stitch(f"front_{s}", "inseam", f"back_{s}", "inseam")
    spec.stitch("front_l", "crotch", "front_r", "crotch")
    spec.stitch("back_r", "crotch", "back_l", "crotch")
    if waistband:
        _waistband(spec, "front", ["front_r", "front_l"], top, 0.04)
        _waistband(spec, "back", ["back_l", "back_r"], top, 0.04)
        spec.stitch("waistband_front", "side_r", "waistband_back", "side_l")
        spec.stitch("waistband_back", "side_r", "waistband_front", "side_l")
    return spec.to_dict()


# -- tops and dresses ---------------------------------------------------------------------------


def _sleeve_rotation(J, side):
    """Placement rotation [deg] of a sleeve panel on ``side``'s arm: panel +y up the arm
    (towards the shoulder), panel normal out of the arm, away from the body."""
    d0 = np.asarray(J[f"{side}_elbow"]) - np.asarray(J[f"{side}_shoulder"])
    d0 /= np.linalg.norm(d0)
    y = -d0
    out = np.array([1.0 if side == "left" else -1.0, 0.0, 0.0])
    z = out - (out @ d0) * d0
    z /= np.linalg.norm(z)
    x = np.cross(y, z)
    return matrix_to_euler_xyz(np.stack([x, y, z], axis=1)).round(4).tolist()


class TopCut(NamedTuple):
    """The cut of :func:`top` [m]: ``length`` from the neck point down to the hem; ``ease`` added
    to the bust girth; ``hem_ease`` to the bust girth at the hem; ``sleeve`` the one-piece
    sleeves' underarm seam length (None: sleeveless); ``neck_depth`` of the front neckline;
    ``waist_shape``: side seams shaped in at the waist over the hips (a sheath dress), with
    ``hip_ease`` added to the hip girth."""

    length: float
    ease: float
    hem_ease: float
    sleeve: float | None = None
    neck_depth: float = 0.08
    waist_shape: bool = False
    hip_ease: float = 0.06


def _bodice_panel(spec, side: str, m, c: TopCut, frame: dict) -> None:
    """The front or back bodice panel; frame: the panel's heights and widths [m] (:func:`top`)."""
    f = frame
    yt, ysh, ya, hip_y, waist_y = f["yt"], f["ysh"], f["ya"], f["hip_y"], f["waist_y"]
    cw, sw, nw, hw = f["cw"], f["sw"], f["nw"], f["hw"]
    nd = c.neck_depth if side == "front" else 0.025
    shaped = c.waist_shape and hip_y > 0.05
    pts, edges = [(-hw, 0.0), (hw, 0.0)], [("hem", None)]
    if shaped:
        wq = (m["waist"] + c.ease + 0.02) / 4
        hq = (m["hip"] + c.hip_ease) / 4
        pts += [(hq, hip_y), (wq, waist_y)]
        edges += [
            ("side_r0", None),
            ("side_r1", ("q", [(0.5 * (hq + wq) + 0.01, 0.5 * (hip_y + waist_y))])),
            ("side_r2", None),
        ]
    else:
        edges += [("side_r2", None)]
    arm_ctrl = f["arm_ctrl"]
    pts += [(cw, ya), (sw, ysh), (nw, yt), (-nw, yt), (-sw, ysh), (-cw, ya)]
    edges += [
        ("arm_r", ("q", [arm_ctrl])),
        ("shoulder_r", None),
        ("neck", ("c", [(nw * 0.9, yt - nd), (-nw * 0.9, yt - nd)])),
        ("shoulder_l", None),
        ("arm_l", ("q", [(-arm_ctrl[0], arm_ctrl[1])])),
    ]
    if shaped:
        pts += [(-wq, waist_y), (-hq, hip_y)]
        edges += [
            ("side_l2", None),
            ("side_l1", ("q", [(-0.5 * (hq + wq) - 0.01, 0.5 * (hip_y + waist_y))])),
            ("side_l0", None),
        ]
    else:
        edges += [("side_l2", None)]
    spec.panel(
        side,
        pts,
        edges,
        translation=(0, f["hem_y"], Z_HINT if side == "front" else -Z_HINT),
        rotation=(0, 0, 0) if side == "front" else ROT_BACK,
    )


def _sleeves(spec, m, J, c: TopCut, frame: dict) -> None:
    """One-piece sleeves whose cap is as long as the armhole (plus ease), sewn in."""
    f = frame
    a = np.array([f["cw"], f["ya"]]), np.array(f["arm_ctrl"]), np.array([f["sw"], f["ysh"]])
    arm_len = _qlen(*a) + 0.01  # cap ease
    bw = (m["upper_arm"] + 0.07 + 0.3 * c.ease) / 2
    lo, hi = 0.02, 0.3  # cap height [m] whose curved cap edge is as long as the armhole
    for _ in range(40):
        cap = 0.5 * (lo + hi)
        ln = _qlen(np.array([bw, 0.0]), np.array([0.55 * bw, 0.75 * cap]), np.array([0.0, cap]))
        lo, hi = (cap, hi) if ln < arm_len else (lo, cap)
    cuff = bw * (0.95 if c.sleeve < 0.35 else 0.6)
    L = cap + c.sleeve  # the sleeve's underarm seam is ``sleeve`` long
    for arm in ("left", "right"):
        pts = [(-cuff, 0), (cuff, 0), (bw, L - cap), (0, L), (-bw, L - cap)]
        edges = [
            ("cuff", None),
            ("under_r", None),
            ("cap_r", ("q", [(0.55 * bw, L - 0.25 * cap)])),
            ("cap_l", ("q", [(-0.55 * bw, L - 0.25 * cap)])),
            ("under_l", None),
        ]
        sh = np.asarray(J[f"{arm}_shoulder"])
        el = np.asarray(J[f"{arm}_elbow"])
        centre = (
            sh
            + 0.5 * min(1.0, L / np.linalg.norm(el - sh)) * (el - sh)
            + np.array([0.08 if arm == "left" else -0.08, 0, 0])
        )
        R = np.asarray(_rot(_sleeve_rotation(J, arm)))
        t = centre - R @ np.array([0.0, L / 2, 0.0])
        spec.panel(f"sleeve_{arm}", pts, edges, translation=t, rotation=_sleeve_rotation(J, arm))
        spec.stitch(f"sleeve_{arm}", "under_r", f"sleeve_{arm}", "under_l")
    # left sleeve: panel +x faces the back; right sleeve: panel +x faces the front
    spec.stitch("sleeve_left", "cap_r", "back", "arm_l")
    spec.stitch("sleeve_left", "cap_l", "front", "arm_r")
    spec.stitch("sleeve_right", "cap_r", "front", "arm_l")
    spec.stitch("sleeve_right", "cap_l", "back", "arm_r")


def top(m, J, *, name="top", **cut):
    """Front and back bodice (or sheath dress when ``length`` reaches below the hips) and
    optional one-piece sleeves. cut: the fields of :class:`TopCut` by name (length, ease and
    hem_ease required)."""
    c = TopCut(**cut)
    spec = Spec(name)
    neck_y = m["neck_height"] + 0.01
    hem_y = neck_y - c.length
    yt = neck_y - hem_y
    cw = (m["bust"] + c.ease) / 4
    sw = max(m["shoulder_width"] / 2 + 0.01, 0.75 * cw)
    ysh = yt - 0.045
    arm_depth = 0.19 + c.ease * 0.1
    ya = ysh - arm_depth
    waist_y = m["waist_height"] - hem_y
    frame = dict(
        hem_y=hem_y,
        yt=yt,
        ysh=ysh,
        ya=ya,
        waist_y=waist_y,
        hip_y=waist_y - 0.2,
        cw=cw,
        sw=sw,
        nw=m["neck"] / 2 / math.pi + 0.015,
        hw=(m["bust"] + c.hem_ease) / 4,
        arm_ctrl=(sw + 0.15 * (cw - sw) - 0.02, ya + 0.35 * arm_depth),
    )
    for side in ("front", "back"):
        _bodice_panel(spec, side, m, c, frame)
    for a, b in (("front", "back"), ("back", "front")):
        spec.stitch(a, "shoulder_r", b, "shoulder_l")
        for e in [k for k in spec.names[a] if k.startswith("side_r")]:
            spec.stitch(a, e, b, "side_l" + e[-1])
    if c.sleeve is not None:
        _sleeves(spec, m, J, c, frame)
    return spec.to_dict()


def _qlen(a, c, b, n=200):
    """Length [m] of the quadratic Bezier a-c-b (points (2,))."""
    t = np.linspace(0, 1, n)[:, None]
    p = (1 - t) ** 2 * a + 2 * t * (1 - t) * c + t**2 * b
    return float(np.linalg.norm(np.diff(p, axis=0), axis=1).sum())


def _rot(angles):
    from unsew.pattern.model import euler_xyz_to_matrix

    return euler_xyz_to_matrix(angles)


#: name -> (garment type, function(measurements, joints, **overrides) -> specification dict);
#: overrides replace the design's own keywords (`python -m benchmarks foreign design`)
DESIGNS = {
    "skirt_aline_knee": (
        "skirt",
        lambda m, J, **kw: skirt(
            m, J, **{**dict(length=0.55, flare=0.06, darts=2, waistband=True, name="skirt_aline_knee"), **kw}
        ),
    ),
    "skirt_pencil_mini": (
        "skirt",
        lambda m, J, **kw: skirt(
            m, J, **{**dict(length=0.40, flare=0.0, darts=2, waistband=True, name="skirt_pencil_mini"), **kw}
        ),
    ),
    "skirt_flared_midi": (
        "skirt",
        lambda m, J, **kw: skirt(
            m,
            J,
            **{**dict(length=0.68, flare=0.16, darts=0, waistband=False, name="skirt_flared_midi"), **kw},
        ),
    ),
    "skirt_circle_knee": (
        "skirt",
        lambda m, J, **kw: circle_skirt(
            m, J, **{**dict(length=0.50, waistband=True, name="skirt_circle_knee"), **kw}
        ),
    ),
    "trousers_straight": (
        "pants",
        lambda m, J, **kw: trousers(
            m,
            J,
            **{**dict(hem_y=0.10, hem_girth=0.44, darts=1, waistband=True, name="trousers_straight"), **kw},
        ),
    ),
    "trousers_tapered": (
        "pants",
        lambda m, J, **kw: trousers(
            m,
            J,
            **{**dict(hem_y=0.11, hem_girth=0.36, darts=1, waistband=True, name="trousers_tapered"), **kw},
        ),
    ),
    "trousers_wide": (
        "pants",
        lambda m, J, **kw: trousers(
            m, J, **{**dict(hem_y=0.10, hem_girth=0.60, darts=0, waistband=False, name="trousers_wide"), **kw}
        ),
    ),
    "shorts_knee": (
        "shorts",
        lambda m, J, **kw: trousers(
            m,
            J,
            **{
                **dict(
                    hem_y=m["crotch_height"] - 0.28,
                    hem_girth=m["thigh"] + 0.10,
                    darts=1,
                    waistband=True,
                    name="shorts_knee",
                ),
                **kw,
            },
        ),
    ),
    "shorts_short": (
        "shorts",
        lambda m, J, **kw: trousers(
            m,
            J,
            **{
                **dict(
                    hem_y=m["crotch_height"] - 0.10,
                    hem_girth=m["thigh"] + 0.12,
                    darts=0,
                    waistband=True,
                    name="shorts_short",
                ),
                **kw,
            },
        ),
    ),
    "shorts_wide": (
        "shorts",
        lambda m, J, **kw: trousers(
            m,
            J,
            **{
                **dict(
                    hem_y=m["crotch_height"] - 0.18,
                    hem_girth=m["thigh"] + 0.22,
                    darts=0,
                    waistband=False,
                    name="shorts_wide",
                ),
                **kw,
            },
        ),
    ),
    "tee_fitted_short": (
        "tshirt",
        lambda m, J, **kw: top(
            m,
            J,
            **{**dict(length=0.62, ease=0.08, hem_ease=0.14, sleeve=0.06, name="tee_fitted_short"), **kw},
        ),
    ),
    "tee_loose_long": (
        "tshirt",
        lambda m, J, **kw: top(
            m,
            J,
            **{
                **dict(
                    length=0.68, ease=0.18, hem_ease=0.22, sleeve=0.40, neck_depth=0.06, name="tee_loose_long"
                ),
                **kw,
            },
        ),
    ),
    "tank_top": (
        "tshirt",
        lambda m, J, **kw: top(
            m,
            J,
            **{
                **dict(length=0.60, ease=0.08, hem_ease=0.12, sleeve=None, neck_depth=0.10, name="tank_top"),
                **kw,
            },
        ),
    ),
    "dress_sheath_sleeveless": (
        "dress",
        lambda m, J, **kw: top(
            m,
            J,
            **{
                **dict(
                    length=0.95,
                    ease=0.08,
                    hem_ease=0.16,
                    sleeve=None,
                    waist_shape=True,
                    name="dress_sheath_sleeveless",
                ),
                **kw,
            },
        ),
    ),
    "dress_shift_sleeved": (
        "dress",
        lambda m, J, **kw: top(
            m,
            J,
            **{
                **dict(
                    length=0.90,
                    ease=0.12,
                    hem_ease=0.30,
                    sleeve=0.07,
                    waist_shape=True,
                    hip_ease=0.16,
                    name="dress_shift_sleeved",
                ),
                **kw,
            },
        ),
    ),
    # fresh designs: lengths and cuts the fit had not met
    "skirt_aline_midi": (
        "skirt",
        lambda m, J, **kw: skirt(
            m, J, **{**dict(length=0.72, flare=0.10, darts=2, waistband=True, name="skirt_aline_midi"), **kw}
        ),
    ),
    "skirt_circle_mini": (
        "skirt",
        lambda m, J, **kw: circle_skirt(
            m, J, **{**dict(length=0.38, waistband=True, name="skirt_circle_mini"), **kw}
        ),
    ),
    "trousers_capri": (
        "pants",
        lambda m, J, **kw: trousers(
            m, J, **{**dict(hem_y=0.30, hem_girth=0.40, darts=1, waistband=True, name="trousers_capri"), **kw}
        ),
    ),
    "tee_fitted_long": (
        "tshirt",
        lambda m, J, **kw: top(
            m, J, **{**dict(length=0.62, ease=0.08, hem_ease=0.14, sleeve=0.45, name="tee_fitted_long"), **kw}
        ),
    ),
    "dress_shift_sleeveless": (
        "dress",
        lambda m, J, **kw: top(
            m,
            J,
            **{
                **dict(
                    length=0.85,
                    ease=0.12,
                    hem_ease=0.30,
                    sleeve=None,
                    waist_shape=True,
                    hip_ease=0.16,
                    name="dress_shift_sleeveless",
                ),
                **kw,
            },
        ),
    ),
    # fresh designs: parameters no earlier design had (a knee skirt flared without a band, boot-cut
    # trousers, mid-thigh shorts with darts, a loose short-sleeved tee, a sheath dress with sleeves,
    # an A-line mini)
    "skirt_flared_knee": (
        "skirt",
        lambda m, J, **kw: skirt(
            m,
            J,
            **{**dict(length=0.55, flare=0.12, darts=0, waistband=False, name="skirt_flared_knee"), **kw},
        ),
    ),
    "trousers_bootcut": (
        "pants",
        lambda m, J, **kw: trousers(
            m,
            J,
            **{**dict(hem_y=0.09, hem_girth=0.50, darts=1, waistband=True, name="trousers_bootcut"), **kw},
        ),
    ),
    "shorts_mid": (
        "shorts",
        lambda m, J, **kw: trousers(
            m,
            J,
            **{
                **dict(
                    hem_y=m["crotch_height"] - 0.18,
                    hem_girth=m["thigh"] + 0.14,
                    darts=1,
                    waistband=True,
                    name="shorts_mid",
                ),
                **kw,
            },
        ),
    ),
    "tee_loose_short": (
        "tshirt",
        lambda m, J, **kw: top(
            m,
            J,
            **{
                **dict(
                    length=0.64,
                    ease=0.18,
                    hem_ease=0.22,
                    sleeve=0.12,
                    neck_depth=0.06,
                    name="tee_loose_short",
                ),
                **kw,
            },
        ),
    ),
    "dress_sheath_sleeved": (
        "dress",
        lambda m, J, **kw: top(
            m,
            J,
            **{
                **dict(
                    length=0.95,
                    ease=0.08,
                    hem_ease=0.16,
                    sleeve=0.07,
                    waist_shape=True,
                    name="dress_sheath_sleeved",
                ),
                **kw,
            },
        ),
    ),
    "skirt_aline_mini": (
        "skirt",
        lambda m, J, **kw: skirt(
            m, J, **{**dict(length=0.42, flare=0.05, darts=2, waistband=True, name="skirt_aline_mini"), **kw}
        ),
    ),
    # more fresh designs
    "skirt_pencil_knee": (
        "skirt",
        lambda m, J, **kw: skirt(
            m, J, **{**dict(length=0.58, flare=0.02, darts=2, waistband=True, name="skirt_pencil_knee"), **kw}
        ),
    ),
    "trousers_wide_band": (
        "pants",
        lambda m, J, **kw: trousers(
            m,
            J,
            **{**dict(hem_y=0.10, hem_girth=0.54, darts=1, waistband=True, name="trousers_wide_band"), **kw},
        ),
    ),
    "shorts_bermuda": (
        "shorts",
        lambda m, J, **kw: trousers(
            m,
            J,
            **{
                **dict(
                    hem_y=m["crotch_height"] - 0.24,
                    hem_girth=m["thigh"] + 0.16,
                    darts=0,
                    waistband=True,
                    name="shorts_bermuda",
                ),
                **kw,
            },
        ),
    ),
    "tee_mid_sleeve": (
        "tshirt",
        lambda m, J, **kw: top(
            m,
            J,
            **{
                **dict(
                    length=0.66, ease=0.12, hem_ease=0.16, sleeve=0.25, neck_depth=0.07, name="tee_mid_sleeve"
                ),
                **kw,
            },
        ),
    ),
    "dress_shift_short": (
        "dress",
        lambda m, J, **kw: top(
            m,
            J,
            **{
                **dict(
                    length=0.80,
                    ease=0.12,
                    hem_ease=0.24,
                    sleeve=0.15,
                    waist_shape=True,
                    hip_ease=0.14,
                    name="dress_shift_short",
                ),
                **kw,
            },
        ),
    ),
    "skirt_flared_mini": (
        "skirt",
        lambda m, J, **kw: skirt(
            m, J, **{**dict(length=0.40, flare=0.10, darts=0, waistband=True, name="skirt_flared_mini"), **kw}
        ),
    ),
    # fresh designs: a tea-length A-line, slim trousers without a band, very short shorts, a boxy
    # cropped tee with elbow sleeves, a straight tunic dress with elbow sleeves
    "skirt_aline_tea": (
        "skirt",
        lambda m, J, **kw: skirt(
            m, J, **{**dict(length=0.63, flare=0.14, darts=2, waistband=True, name="skirt_aline_tea"), **kw}
        ),
    ),
    "trousers_slim": (
        "pants",
        lambda m, J, **kw: trousers(
            m, J, **{**dict(hem_y=0.08, hem_girth=0.34, darts=1, waistband=False, name="trousers_slim"), **kw}
        ),
    ),
    "shorts_hot": (
        "shorts",
        lambda m, J, **kw: trousers(
            m,
            J,
            **{
                **dict(
                    hem_y=m["crotch_height"] - 0.06,
                    hem_girth=m["thigh"] + 0.10,
                    darts=0,
                    waistband=True,
                    name="shorts_hot",
                ),
                **kw,
            },
        ),
    ),
    "tee_boxy_elbow": (
        "tshirt",
        lambda m, J, **kw: top(
            m,
            J,
            **{
                **dict(
                    length=0.56, ease=0.22, hem_ease=0.24, sleeve=0.30, neck_depth=0.08, name="tee_boxy_elbow"
                ),
                **kw,
            },
        ),
    ),
    "dress_tunic_sleeved": (
        "dress",
        lambda m, J, **kw: top(
            m,
            J,
            **{
                **dict(
                    length=0.84,
                    ease=0.10,
                    hem_ease=0.20,
                    sleeve=0.20,
                    hip_ease=0.12,
                    name="dress_tunic_sleeved",
                ),
                **kw,
            },
        ),
    ),
    # fresh designs: a straight sleeveless knee dress (a shift without waist shaping)
    "dress_straight_tank": (
        "dress",
        lambda m, J, **kw: top(
            m,
            J,
            **{**dict(length=0.92, ease=0.10, hem_ease=0.28, sleeve=None, name="dress_straight_tank"), **kw},
        ),
    ),
    # fresh designs: dresses with long sleeves (the library's dresses have short sleeves or none)
    "dress_shift_long_sleeve": (
        "dress",
        lambda m, J, **kw: top(
            m,
            J,
            **{
                **dict(
                    length=0.92,
                    ease=0.12,
                    hem_ease=0.30,
                    sleeve=0.42,
                    waist_shape=True,
                    hip_ease=0.16,
                    name="dress_shift_long_sleeve",
                ),
                **kw,
            },
        ),
    ),
    "dress_tunic_long_sleeve": (
        "dress",
        lambda m, J, **kw: top(
            m,
            J,
            **{
                **dict(length=0.86, ease=0.12, hem_ease=0.24, sleeve=0.44, name="dress_tunic_long_sleeve"),
                **kw,
            },
        ),
    ),
}
