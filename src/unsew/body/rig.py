"""Rig a body from its mesh alone: the 17 joints of FORMATS.md (pelvis, spine, chest, neck, head,
left/right shoulder, elbow, wrist, hip, knee, ankle) for a body in A-pose, T-pose or with a limb
moved, when no skeleton.json comes with it.

The method is geometric (no body model, no dependency beyond scipy):

1. The five extremities (head, finger tips, toes) are the farthest points of the surface by
   geodesic distance (edge-graph Dijkstra), found one after another from the body's centre of
   mass. The two lowest are the feet (left at +X); of the other three the head is as far from
   one as from the other, and the hands are told apart by X. The crown is the highest point of
   the part of the surface nearer the head's extremity than any other (the extremity itself may
   be inside a mouth). Toes behind the heels mean the body faces -Z: refused.
2. Each limb is read as rings: level sets of the geodesic distance from its extremity, which cut
   a limb across its axis whatever its pose. A ring's centroid is a point of the limb's axis and
   its length the limb's girth there. The limb's root is where the girth jumps (the ring has
   reached the torso).
3. The trunk is read as horizontal sections followed down from the crown (the loop around the
   crown's vertical axis): the neck joint a little below the neck's narrowest section, the head
   joint a share of the way up to the crown, the crotch where no section surrounds the axis any
   more, the pelvis and hips above it, spine and chest at shares of the way from pelvis to neck,
   each at a share of its section's depth. The shoulders are fixed offsets from the neck joint (a
   shoulder joint does not move when its arm turns, so the arm's pose does not matter).
4. On the limbs' axes: the wrist at the first ring, coming from the hand, as narrow as the
   forearm; the elbow at the axis point whose distances to shoulder and wrist have the upper
   arm's share (bent or straight); the ankle a fixed geodesic way back from the heel's last ring
   (the longest ring over the foot); the knee at the axis point a shin's length from the ankle.

All lengths are shares of the body height H (crown to soles; the shin grows as H^0.61), read on
anny bodies (MakeHuman's
skeleton), whose joints the benchmark ``python -m benchmarks rig`` (at 81f6fbb) compared against. The torso is
assumed upright (the spine is not bent); a limb may be moved, a leg up to about 45 degrees.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from unsew.body.skeleton import Skeleton
from unsew.errors import InputError
from unsew.geometry.topology import unique_edges

__all__ = ["rig_skeleton", "RIG_JOINTS", "level_loops", "surrounds"]

#: The joints :func:`rig_skeleton` places: name -> (parent, part) (FORMATS.md's 17).
RIG_JOINTS: dict[str, tuple[str | None, str]] = {
    "pelvis": (None, "torso"),
    "spine": ("pelvis", "torso"),
    "chest": ("spine", "torso"),
    "neck": ("chest", "torso"),
    "head": ("neck", "head"),
    **{
        f"{s}_{j}": (p if p in ("chest", "pelvis") else f"{s}_{p}", part.format(s=s))
        for s in ("left", "right")
        for j, p, part in (
            ("shoulder", "chest", "torso"),
            ("elbow", "shoulder", "{s}_arm"),
            ("wrist", "elbow", "{s}_arm"),
            ("hip", "pelvis", "torso"),
            ("knee", "hip", "{s}_leg"),
            ("ankle", "knee", "{s}_leg"),
        )
    },
}

# Shares of the body height H (head top to soles) and of limb axes, read on anny bodies.
_RING_STEP = 0.006  # spacing of the rings along a limb, share of H
_ROOT_JUMP = 1.3  # a ring longer than this many times the limb's recent narrowest one is on the torso
_NECK_BELOW_MIN = 0.013  # the neck joint below the neck's narrowest section, share of H
_HEAD_SHARE = 0.395  # the head joint's share of the way from the neck joint to the head top
_PELVIS_ABOVE_CROTCH = 0.059  # share of H
_HIP_BELOW_PELVIS = 0.0055  # share of H
_HIP_X = 0.0625  # hip joints' distance from the pelvis' mid-plane, share of H
_SHOULDER = (0.101, -0.0525, 0.011)  # shoulder joint from the neck joint (x outwards), share of H
_WRIST_WINDOW = (0.07, 0.22)  # the wrist's range of geodesic distance from the finger tip, share of H
_NARROW = 1.08  # the wrist: the first ring within this factor of the forearm's narrowest
_ARM_RATIO = 1.11  # upper arm / forearm length
_SHIN = (0.41, 1.65, 0.61)  # knee to ankle [m] = a * (H / H0) ** p: (a [m], H0 [m], p)
_HEEL_EXIT = 0.85  # a ring this much shorter than the longest before it is on the shin
_HEEL_NEAR = 0.97  # rings within this factor of the longest over the foot go round the heel
_ANKLE_BEFORE_HEEL = 0.027  # the ankle's geodesic distance before the heel's last ring, share of H
_SPINE_SHARE = {"spine": 0.265, "chest": 0.673}  # share of the way from pelvis to neck
#: joints' depth as a share of their section's depth, from its back (-Z) to its front (+Z)
_ZREL = {"neck": 0.34, "pelvis": 0.47, "hip": 0.46, "spine": 0.18, "chest": 0.21}


@dataclass
class _Limb:
    """Rings of one limb from its extremity: t (n,) geodesic level [m], c (n, 3) centroids [m],
    g (n,) girth [m] of the ring's largest loop, nc (n,) number of loops; root: index of the
    first ring on the torso."""

    end: int
    t: np.ndarray
    c: np.ndarray
    g: np.ndarray
    nc: np.ndarray
    root: int


def _graph(verts: np.ndarray, faces: np.ndarray):
    import scipy.sparse as sp

    e = unique_edges(faces)[0]  # (E, 2)
    w = np.linalg.norm(verts[e[:, 0]] - verts[e[:, 1]], axis=1)
    n = len(verts)
    a = sp.coo_matrix((w, (e[:, 0], e[:, 1])), shape=(n, n)).tocsr()
    return a + a.T


def level_loops(verts: np.ndarray, faces: np.ndarray, g: np.ndarray, t: float, lo=None, hi=None, order=None):
    """The level set {g = t} of a vertex field g (V,) on the surface, as loops.

    verts: (V, 3) float64 [m]; faces: (F, 3) int; g: (V,) float64; t: the level (g's unit).
    ``lo``/``hi``/``order``: g's per-face min and max and ``argsort(lo)``, to reuse over many
    levels. Returns a list of (centroid (3,) [m], length [m], points (k, 3) [m]) per loop,
    longest first."""
    import scipy.sparse as sp
    from scipy.sparse.csgraph import connected_components

    n = len(verts)
    ga = g[faces]  # (F, 3)
    if lo is None:
        lo, hi = ga.min(axis=1), ga.max(axis=1)
        order = np.argsort(lo)
    cand = order[: np.searchsorted(lo[order], t)]
    cand = cand[hi[cand] > t]
    if len(cand) == 0:
        return []
    f = faces[cand]
    s = ga[cand] - t  # (m, 3)
    neg = s < 0
    pts, keys = [], []
    for a, b in ((0, 1), (1, 2), (2, 0)):
        cross = neg[:, a] != neg[:, b]
        ta = s[:, a] / np.where(cross, s[:, a] - s[:, b], 1.0)
        pts.append(verts[f[:, a]] + (verts[f[:, b]] - verts[f[:, a]]) * ta[:, None])
        keys.append(np.where(cross, np.minimum(f[:, a], f[:, b]) * n + np.maximum(f[:, a], f[:, b]), -1))
    P = np.stack(pts, axis=1)  # (m, 3, 3)
    K = np.stack(keys, axis=1)  # (m, 3)
    sel = K >= 0
    keep = sel.sum(axis=1) == 2
    Pa = P[keep][sel[keep]].reshape(-1, 2, 3)  # one segment per crossed face
    Ka = K[keep][sel[keep]].reshape(-1, 2)
    seg = np.linalg.norm(Pa[:, 0] - Pa[:, 1], axis=1)
    mid = 0.5 * (Pa[:, 0] + Pa[:, 1])
    u, inv = np.unique(Ka, return_inverse=True)
    inv = inv.reshape(-1, 2)
    adj = sp.coo_matrix((np.ones(len(inv)), (inv[:, 0], inv[:, 1])), shape=(len(u), len(u)))
    nc, lab = connected_components(adj, directed=False)
    lab = lab[inv[:, 0]]
    w = np.bincount(lab, weights=seg, minlength=nc)
    out = []
    for k in np.argsort(-w):
        m = lab == k
        out.append(((mid[m] * seg[m, None]).sum(axis=0) / max(seg[m].sum(), 1e-12), float(w[k]), mid[m]))
    return out


def _rings(verts: np.ndarray, faces: np.ndarray, g: np.ndarray, levels: np.ndarray):
    """Level sets of a vertex field g (V,) at each level: centroid (3,) and length [m] of the
    longest loop, and the number of loops. Returns (c (n, 3), length (n,), loops (n,))."""
    ga = g[faces]
    lo, hi = ga.min(axis=1), ga.max(axis=1)
    order = np.argsort(lo)
    cs, ls, ncs = [], [], []
    for t in levels:
        loops = level_loops(verts, faces, g, t, lo, hi, order)
        if not loops:
            cs.append(np.full(3, np.nan))
            ls.append(0.0)
            ncs.append(0)
            continue
        cs.append(loops[0][0])
        ls.append(loops[0][1])
        ncs.append(len(loops))
    return np.array(cs), np.array(ls), np.array(ncs)


def surrounds(p: np.ndarray, loop: np.ndarray) -> bool:
    """Whether 2D point p (2,) is inside the region of a loop's points (k, 2), read by angle:
    the loop's points surround p when every direction from p has a point within 60 degrees."""
    d = loop - p
    ang = np.sort(np.arctan2(d[:, 1], d[:, 0]))
    gaps = np.diff(np.concatenate([ang, ang[:1] + 2 * np.pi]))
    return bool(gaps.max() < np.pi / 3)


@dataclass
class _Column:
    """Horizontal sections of the trunk followed down from the head top: y (n,) [m], c (n, 3)
    centroid, g (n,) girth, lo/hi (n, 3) bounding box of the followed loop [m]; crotch: the
    first level (going down) whose sections no longer surround the trunk's axis."""

    y: np.ndarray
    c: np.ndarray
    g: np.ndarray
    lo: np.ndarray
    hi: np.ndarray
    crotch: int


def _column(
    verts: np.ndarray, faces: np.ndarray, top: np.ndarray, y_end: float, step: float, half_width: float
) -> _Column:
    g = verts[:, 1]
    ga = g[faces]
    lo_f, hi_f = ga.min(axis=1), ga.max(axis=1)
    order = np.argsort(lo_f)
    axis = top[[0, 2]].copy()
    ys = np.arange(top[1] - step, y_end, -step)
    cs, gs, los, his = [], [], [], []
    crotch = len(ys)
    for i, y in enumerate(ys):
        loops = level_loops(verts, faces, g, y, lo_f, hi_f, order)
        best = None
        for c, length, pts in loops:
            if surrounds(axis, pts[:, [0, 2]]) and (best is None or length > best[1]):
                best = (c, length, pts)
        if best is None:
            if i > 10:
                crotch = i
                break
            best = min(loops, key=lambda lp: np.linalg.norm(lp[0][[0, 2]] - axis)) if loops else None
            if best is None:
                continue
        c, length, pts = best
        near = np.linalg.norm(pts[:, [0, 2]] - axis, axis=1) < half_width  # the trunk, not arms that touch it
        if near.sum() >= 3:
            pts = pts[near]
            c = pts.mean(axis=0)
        cs.append(c)
        gs.append(length)
        los.append(pts.min(axis=0))
        his.append(pts.max(axis=0))
    n = len(cs)
    return _Column(ys[:n], np.array(cs), np.array(gs), np.array(los), np.array(his), min(crotch, n))


def _extremities(verts: np.ndarray, faces: np.ndarray, graph):
    """Vertex indices of the five extremities and the geodesic distances (5, V) from them."""
    import trimesh
    from scipy.sparse.csgraph import dijkstra

    com = trimesh.Trimesh(verts, faces, process=False).center_mass
    seed = int(np.argmin(np.linalg.norm(verts - com, axis=1)))
    dmin = dijkstra(graph, indices=seed)
    ends = []
    for _ in range(5):
        e = int(np.argmax(dmin))
        d = dijkstra(graph, indices=e)
        dmin = np.minimum(dmin, d)
        ends.append(e)
    return ends, dijkstra(graph, indices=ends)


def _limb(verts, faces, d, end, *, t_max, step, t_min_root):
    t = np.arange(step, t_max, step)
    c, g, nc = _rings(verts, faces, d, t)
    root = len(t) - 1
    win = max(int(round(0.1 / step)), 3)
    for i in range(len(t)):
        if t[i] < t_min_root:
            continue
        recent = g[max(0, i - win) : i]
        if len(recent) and g[i] > _ROOT_JUMP * recent.min():
            root = i
            break
    return _Limb(end, t, c, g, nc, root)


def _name_ends(V, ends, D) -> tuple[int, int, int, int, int]:
    """Which of the five extremities ``ends`` (vertex indices into V (n, 3) [m], geodesic
    distances D (5, n) [m] from each) is which: (left foot, right foot, left hand, right hand,
    head), as indices into ``ends``. The feet are the two lowest, the left ones at +X; the head
    is as far from one hand as from the other (a hand is much nearer the head)."""
    feet = list(np.argsort(V[ends, 1])[:2])
    others = [i for i in range(5) if i not in feet]
    lf, rf = sorted(feet, key=lambda i: -V[ends[i], 0])  # left foot at +X
    ih = min(others, key=lambda i: abs(float(np.subtract(*[D[i, ends[j]] for j in others if j != i]))))
    hands = [i for i in others if i != ih]
    lh, rh = sorted(hands, key=lambda i: -(V[ends[i], 0] - V[ends[ih], 0]))  # left hand at +X
    return lf, rf, lh, rh, ih


def rig_skeleton(verts: np.ndarray, faces: np.ndarray, *, debug: dict | None = None):
    """The 17 joints of a body estimated from its closed surface (see the module docstring).

    verts: (V, 3) float64 [m], world frame (Y up, facing +Z, left at +X); faces: (F, 3) int64,
    one closed component. Returns a ``Skeleton`` with the joints of :data:`RIG_JOINTS`.
    ``debug``: a dict to fill with the intermediate rings (for previews and tests).
    Raises InputError when the surface does not read as a standing person with two arms and
    two legs.
    """
    V = np.asarray(verts, dtype=np.float64)
    F = np.asarray(faces, dtype=np.int64)
    floor = float(V[:, 1].min())
    graph = _graph(V, F)
    ends, D = _extremities(V, F, graph)
    lf, rf, lh, rh, ih = _name_ends(V, ends, D)
    near_head = np.flatnonzero(np.argmin(D, axis=0) == ih)  # nearer the head's end than any other
    head_top = V[near_head[np.argmax(V[near_head, 1])]]  # the crown, not the forehead or chin
    H = float(head_top[1] - floor)
    if not (0.5 < H < 3.0):
        raise InputError(f"body is {H:.2f} m from soles to head top; cannot rig it (check --units/--up)")
    if (
        V[[ends[lf], ends[rf]], 1].max() - floor > 0.15 * H
        or not V[ends[rh], 0] < head_top[0] < V[ends[lh], 0]
    ):
        raise InputError(
            "body mesh does not read as a person standing on two feet with the arms apart from the "
            "trunk; give its skeleton.json"
        )
    toes = V[[ends[lf], ends[rf]]]  # the feet's far ends: the toes, in front of the heels
    heels = np.array([V[D[i] < 0.12 * (head_top[1] - floor)].mean(axis=0) for i in (lf, rf)])
    if (toes[:, 2] - heels[:, 2]).max() < 0:
        raise InputError("body faces -Z (its toes point backwards); use --front -z")
    step = _RING_STEP * H

    # -- legs: rings from the toes
    legs = {}
    for side, i in (("left", lf), ("right", rf)):
        legs[side] = _limb(V, F, D[i], ends[i], t_max=0.75 * H, step=step, t_min_root=0.4 * H)
    # -- arms: rings from the finger tips
    arms = {}
    for side, i in (("left", lh), ("right", rh)):
        arms[side] = _limb(V, F, D[i], ends[i], t_max=0.55 * H, step=step, t_min_root=0.25 * H)
    _check_limbs_thin(legs, arms, H)
    if debug is not None:
        named = zip(("left_foot", "right_foot", "left_hand", "right_hand", "head"), (lf, rf, lh, rh, ih))
        debug.update(ends={n: ends[i] for n, i in named}, legs=legs, arms=arms, H=H)
    col = _column(V, F, head_top, floor + 0.3 * H, 0.003 * H, 0.13 * H)
    J = _torso_joints(col, floor, H)
    for side in ("left", "right"):
        J.update(_arm_joints(arms[side], J[f"{side}_shoulder"], side, H))
        J.update(_leg_joints(legs[side], J[f"{side}_hip"], side, H))
    names = list(RIG_JOINTS)
    parents = np.array([-1 if RIG_JOINTS[n][0] is None else names.index(RIG_JOINTS[n][0]) for n in names])
    return Skeleton(names, parents, np.array([J[n] for n in names]), [RIG_JOINTS[n][1] for n in names])


def _check_limbs_thin(legs: dict, arms: dict, H: float) -> None:
    """Refuse a shape whose five extremities do not end limbs: a person's ankle (the narrowest
    ring 10-25 % of H from the toes) and wrist (7-22 % from the finger tips) are far thinner
    than a quarter and a fifth of the height; a 1.7 m capsule's rings there are not."""
    for limbs, (a, b), most, what in (
        (legs, (0.10, 0.25), 0.25, "ankle"),
        (arms, _WRIST_WINDOW, 0.20, "wrist"),
    ):
        for side, limb in limbs.items():
            m = (limb.t > a * H) & (limb.t < b * H) & (limb.g > 0)
            if not m.any() or limb.g[m].min() > most * H:
                raise InputError(
                    f"body mesh does not read as a person: no {side} {what} thinner than {most:.0%} of its "
                    f"height {H:.2f} m; give its skeleton.json"
                )


def _arm_joints(arm: _Limb, shoulder: np.ndarray, side: str, H: float) -> dict:
    """Wrist and elbow of one arm from its rings; the shoulder is given (from the trunk)."""
    t, c, g = arm.t, arm.c, arm.g
    win = np.flatnonzero((t > _WRIST_WINDOW[0] * H) & (t < _WRIST_WINDOW[1] * H))
    win = win[win < arm.root]
    if len(win) == 0:
        raise InputError(f"cannot find the {side} wrist: the {side} arm is shorter than a hand")
    gmin = g[win].min()
    iw = int(win[np.argmax(g[win] < _NARROW * gmin)])  # the hand's end of the forearm's narrow part
    wrist = c[iw]
    # the elbow: the axis point whose distances to shoulder and wrist have the upper arm's share
    i1 = iw + int(np.argmin(np.linalg.norm(c[iw : arm.root + 1] - shoulder, axis=1)))
    seg = c[iw : i1 + 1]
    ratio = np.linalg.norm(seg - shoulder, axis=1) / np.maximum(np.linalg.norm(seg - wrist, axis=1), 1e-9)
    elbow = seg[int(np.argmin(np.abs(ratio - _ARM_RATIO)))]
    return {f"{side}_wrist": wrist, f"{side}_elbow": elbow}


def _leg_joints(leg: _Limb, hip: np.ndarray, side: str, H: float) -> dict:
    """Ankle and knee of one leg from its rings; the hip is given (from the trunk)."""
    t, c, g = leg.t, leg.c, leg.g
    step = t[1] - t[0]
    # the ankle: a fixed way back from the heel's last ring (the longest ring over the foot)
    toes = np.flatnonzero((leg.nc > 1) & (t < 0.15 * H))  # rings that cut toes apart
    start = max(0.08 * H, t[toes.max()] if len(toes) else 0.0)
    win = np.flatnonzero((t > start) & (t < 0.25 * H) & (np.arange(len(t)) < leg.root))
    heel = win[g[win] >= _HEEL_NEAR * g[win].max()].max()
    run = np.maximum.accumulate(g[win])
    out = np.flatnonzero(g[win] < _HEEL_EXIT * run)  # the rings have left the heel for the shin
    if len(out):
        before = win[: out[0]]
        heel = before[g[before] >= _HEEL_NEAR * run[out[0]]].max()
    ia = max(int(heel) - int(round(_ANKLE_BEFORE_HEEL * H / step)), 0)
    ankle = c[ia]
    # the knee: the axis point a shin's length from the ankle (anny's shin grows as H^0.61)
    top = int(np.argmin(np.linalg.norm(c[ia : leg.root + 1] - hip, axis=1))) + ia
    shin = _SHIN[0] * (H / _SHIN[1]) ** _SHIN[2]
    k = ia + int(np.argmin(np.abs(np.linalg.norm(c[ia : top + 1] - ankle, axis=1) - shin)))
    knee = c[k]
    return {f"{side}_ankle": ankle, f"{side}_knee": knee}


def _torso_joints(col: _Column, floor: float, H: float) -> dict:
    """Pelvis, hips, spine, chest, neck and head from the trunk's horizontal sections."""
    yr = (col.y - floor) / H
    m = (yr > 0.78) & (yr < 0.9)
    if not m.any():
        raise InputError("cannot find the neck of the body (no narrow section 78-90 % of its height up)")
    neck_min = col.y[np.flatnonzero(m)[np.argmin(col.g[m])]]

    def section(y):
        k = int(np.argmin(np.abs(col.y - y)))
        return col.c[k], col.lo[k], col.hi[k]

    def at(y, zrel, xrel=0.0):
        c, lo, hi = section(y)
        x = c[0] + xrel * (hi[0] - c[0] if xrel > 0 else c[0] - lo[0])
        return np.array([x, y, lo[2] + zrel * (hi[2] - lo[2])])

    top = col.c[0]
    neck = at(neck_min - _NECK_BELOW_MIN * H, _ZREL["neck"])
    head = np.array(
        [top[0], neck[1] + _HEAD_SHARE * (top[1] + 0.5 * (col.y[0] - col.y[1]) - neck[1]), top[2]]
    )
    crotch = col.y[col.crotch - 1]
    pelvis = at(crotch + _PELVIS_ABOVE_CROTCH * H, _ZREL["pelvis"])
    hip_y = pelvis[1] - _HIP_BELOW_PELVIS * H
    out = {"pelvis": pelvis, "neck": neck, "head": head}
    for side, sign in (("left", 1.0), ("right", -1.0)):
        out[f"{side}_hip"] = at(hip_y, _ZREL["hip"]) + np.array([sign * _HIP_X * H, 0.0, 0.0])
        out[f"{side}_shoulder"] = neck + np.array([sign * _SHOULDER[0], _SHOULDER[1], _SHOULDER[2]]) * H
    for n in ("spine", "chest"):
        out[n] = at(pelvis[1] + _SPINE_SHARE[n] * (neck[1] - pelvis[1]), _ZREL[n])
    return out
