"""Side seams graded by girth (grading's ``side_seams="girth"``).

Algorithm 2 grades the open curves (hems, cuffs, necklines, armholes) and leaves the seams
between them where the base has them; a waisted base's waist and hips, points on its side seams,
keep the base's girth there, and the area scaling makes up the missing cloth by lengthening the
garment (docs/decisions/008). Here, for a garment that hangs
from the shoulders, each side-seam point between :data:`BELOW_HIP` under the hips and
:data:`BELOW_ARMPIT` under the armpits moves across its panel by its share of the target's torso
girth at the point's drape height minus the drape's (:func:`torso_girth`): one more term of each
grading pass's edit, no extra drape.

A side-seam point is a control point whose two outline edges are both stitched (a join of two
seam edges, so never the end of a hem or an armhole) and that lies on its panel's side: moved
across the panel (perpendicular to the direction its placement points up), away from the panel's
middle. The points at one height (within :data:`SAME_HEIGHT`: front and back, left and right)
share that height's girth difference equally, each move at most :data:`MAX_MOVE`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = [
    "SideSeams",
    "side_seams_for",
    "torso_girth",
    "side_seam_points",
    "side_seam_moves",
    "BELOW_HIP",
    "BELOW_ARMPIT",
    "SAME_HEIGHT",
    "MAX_MOVE",
    "MIN_SWEEP",
]

#: The graded heights: from this far under the hips [m] ...
BELOW_HIP = 0.05
#: ... up to this far under the armpits [m] (the armhole's bottom is the armhole's to grade).
BELOW_ARMPIT = 0.05
#: Side-seam points whose drape heights lie within this of each other share one girth [m].
SAME_HEIGHT = 0.02
#: The largest move of one point in one pass [m] (a quarter of a 12 cm girth difference).
MAX_MOVE = 0.03
#: A piece of a horizontal slice counts as going round the torso when it sweeps at least this
#: angle about the torso's axis [rad]; a sleeve or a hand beside the hips sweeps far less.
MIN_SWEEP = np.pi


@dataclass(frozen=True)
class SideSeams:
    """What side-seam grading needs of the target and the body: the target mesh (V, 3) [m] and
    (F, 3), the graded heights [lo, hi] [m] and the torso's axis (x, z) [m]."""

    target_verts: np.ndarray
    target_faces: np.ndarray
    lo: float
    hi: float
    axis_xz: np.ndarray


def side_seams_for(body, target_verts, target_faces, target_contours) -> SideSeams | None:
    """The side-seam grading context of a target, or None when its garment does not hang from
    the shoulders (no contour on the head, i.e. no neckline: skirts, trousers)."""
    if not any(c.part == "head" for c in target_contours):
        return None
    from unsew.body.measure import measure_body
    from unsew.pattern.base._frame import body_frame

    f = body_frame(measure_body(body))
    sk = body.skeleton
    hips = 0.5 * (np.asarray(sk.position("left_hip")) + np.asarray(sk.position("right_hip")))
    return SideSeams(
        np.asarray(target_verts, dtype=np.float64),
        np.asarray(target_faces, dtype=np.int64),
        float(f.hip_y - BELOW_HIP),
        float(f.armpit_y - BELOW_ARMPIT),
        hips[[0, 2]].astype(np.float64),
    )


def torso_girth(verts: np.ndarray, faces: np.ndarray, y: float, axis_xz: np.ndarray) -> float | None:
    """The girth [m] of a garment mesh (``verts`` (V, 3) float [m], ``faces`` (F, 3) int) round
    the torso at height ``y`` [m]: the total length of the pieces of its horizontal slice that
    sweep at least :data:`MIN_SWEEP` about the torso's axis ``axis_xz`` (2,) (x, z) [m]; None
    when no piece does."""
    import trimesh

    mesh = trimesh.Trimesh(
        np.asarray(verts, dtype=np.float64), np.asarray(faces, dtype=np.int64), process=False
    )
    path = mesh.section(plane_origin=[0.0, float(y), 0.0], plane_normal=[0.0, 1.0, 0.0])
    if path is None:
        return None
    total, found = 0.0, False
    for line in path.discrete:
        p = np.asarray(line, dtype=np.float64)
        if len(p) < 3:
            continue
        a = np.unwrap(np.arctan2(p[:, 2] - axis_xz[1], p[:, 0] - axis_xz[0]))
        if float(a.max() - a.min()) >= MIN_SWEEP:
            total += float(np.linalg.norm(np.diff(p, axis=0), axis=1).sum())
            found = True
    return total if found else None


def _sewn_to(pattern) -> dict:
    """(panel name, edge index) -> the set of panels its stitches sew it to."""
    out: dict = {}
    for s in pattern.stitches:
        out.setdefault((s.a.panel, s.a.edge), set()).add(s.b.panel)
        out.setdefault((s.b.panel, s.b.edge), set()).add(s.a.panel)
    return out


def side_seam_points(pattern, controls) -> list[tuple[int, np.ndarray]]:
    """The side-seam points of a pattern: (control point index, its unit direction across its
    panel, away from the panel's middle (2,) [-]) for each control point of a panel placed
    upright whose two outline edges are both sewn to other panels (a dart's tip, whose edges are
    sewn to each other, is not one)."""
    from unsew.grading.grade import upright

    sewn = _sewn_to(pattern)
    out = []
    for g in range(len(controls)):
        name = controls.panel_names[int(controls.panel[g])]
        panel = pattern.panels[name]
        v = int(controls.vertex[g])
        edges = [i for i, e in enumerate(panel.edges) if e.start == v or e.end == v]
        if len(edges) != 2 or not all(sewn.get((name, i), set()) - {name} for i in edges):
            continue
        up = upright(panel)
        if up is None:
            continue
        across = np.array([up[1], -up[0]])
        verts = np.asarray(panel.vertices, dtype=np.float64)
        side = float((verts[v] - verts.mean(axis=0)) @ across)
        if abs(side) < 1e-6:
            continue
        out.append((g, across * np.sign(side)))
    return out


def side_seam_moves(
    pattern, controls, control_x: np.ndarray, x: np.ndarray, faces: np.ndarray, ctx: SideSeams
) -> tuple[np.ndarray, list[str]]:
    """Each control point's move [m], (Nc, 2) (zero but at the side-seam points in the graded
    heights), and one line per height graded saying what it moved.

    control_x: the sewn vertex of each control point (Nc,) int64; x: the drape (n_x, 3) [m] on
    ``faces`` (F, 3)."""
    delta = np.zeros((len(controls), 2))
    pts = [(g, d, float(x[int(control_x[g]), 1])) for g, d in side_seam_points(pattern, controls)]
    pts = [p for p in pts if ctx.lo <= p[2] <= ctx.hi]
    notes, done = [], set()
    for g, _, y in sorted(pts, key=lambda p: p[2]):
        if g in done:
            continue
        group = [p for p in pts if abs(p[2] - y) <= SAME_HEIGHT and p[0] not in done]
        done.update(p[0] for p in group)
        yc = float(np.mean([p[2] for p in group]))
        gt = torso_girth(ctx.target_verts, ctx.target_faces, yc, ctx.axis_xz)
        gs = torso_girth(x, faces, yc, ctx.axis_xz)
        if gt is None or gs is None:
            continue
        share = float(np.clip((gt - gs) / len(group), -MAX_MOVE, MAX_MOVE))
        for gi, d, _ in group:
            delta[gi] += share * d
        notes.append(
            f"side seams at y {yc:.2f} m: girth {100 * gs:.1f} cm against the target's {100 * gt:.1f} cm, "
            f"{len(group)} points moved {100 * share:+.1f} cm across"
        )
    return delta, notes
