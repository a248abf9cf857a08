"""Placement of a pattern's panels around a body: the start of the sewing phase.

Each flat panel is wrapped isometrically (arc length along a cross-section = distance across
the panel) onto a surface a little outside the body, so its rest shape is nearly unstretched
and the two edges of every stitch face each other:

- torso panels onto a stack of horizontal ellipses around the torso (front panels in front,
  back panels behind, the panel's own 3D placement telling which side and how high); what
  rises above the shoulders folds over them towards the body's centre plane. Tops are raised
  until their shoulder seams (labelled, or found by geometry) meet over the shoulders; panels
  sewn to them by horizontal seams (a skirt, a waistband, trousers) follow; a lower garment
  stays at its placement's height when that lies on this body's torso, else goes to the waist;
- sleeves (panels out beyond the shoulder, one piece or front and back halves) into one tube
  per arm around its shoulder-elbow-wrist line, so they follow the arm in any pose; a raised
  arm's root joins the torso's stack so armholes wrap round it;
- trouser legs into a stack of ellipses around their leg below the crotch, blended over a few
  cm into the torso stack above it;
- anything else (a collar, a hood) at its own placement, moved with the garment.

On a body with an arm raised (T-pose and the like), seam vertices whose copies land more than
SEAM_MEET apart start at their midpoint; outline stubs (1-5 mm) start about their own length long
(see :func:`_meet_seams`, :func:`_close_stubs`).

:func:`place_as_given` is the other start: the pattern's own placement, front and back panels
bent round the body, what lies inside carried out (a GarmentCode file places its panels for the
body it is sized to); :func:`unsew.dress.dress` drapes from it when the wrapped start drapes
unsound.

Cross-sections come from the body's vertices (grouped by part through the skeleton), plus a
clearance; where the garment is wider than the section, the ellipse grows (in depth for the
torso, in both axes for legs and arms) so that front and back meet. Points that still end up
inside or too close to the body are pushed out along the SDF normal, by at most
``MAX_PUSH`` (a deep point pushed to its nearest surface would exit through the far side of
the body, shared/STACK.md).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from unsew.errors import InputError

__all__ = [
    "place_garment",
    "place_as_given",
    "panel_roles",
    "meets_seams",
    "hint_shift",
    "CLEARANCE",
    "MAX_PUSH",
]

#: Gap between the body's cross-section and the wrapped cloth [m].
CLEARANCE = 0.02
#: Points closer than this to the body after wrapping are pushed out to it [m].
MIN_GAP = 0.008
#: Largest push along the SDF normal [m] (deeper points are left to the sewing's contact).
MAX_PUSH = 0.05
#: Half-height of the blend between leg tubes and the torso stack around the crotch [m].
CROTCH_BLEND = 0.04
#: A girth needed at one height is kept for this far below it (curved hems) [m].
NEED_WINDOW = 0.15
#: Each shoulder edge of a top is brought this close to the body's centre plane [m] (front
#: and back edges 2 * SHOULDER_MEET apart over the shoulder ridge).
SHOULDER_MEET = 0.012
#: An unlabelled shoulder seam below the body's chest (a top sized to a shorter body) lies on
#: average within this of the top of the torso panels [m] (decision 069).
SHOULDER_AT_TOP = 0.05
#: A pattern file places its shoulder seams about this far below its own body's shoulder line
#: [m] ...
HINT_SHOULDER_GAP = 0.03
#: ... and one whose seams lie more than this farther from that on the body it is dressed on is
#: sized to another body, and moved up or down to this one before it is placed [m] (decision 070).
HINT_SHIFT_TOL = 0.15
#: Unlabelled shoulder seams lie within this share of the shoulder joints' half span from the
#: body's centre plane (a wide sleeve's halves, sewn like a bodice's, lie farther out).
HINT_SHOULDER_REACH = 2.0
#: Secant iterations solving a top's lift, and the largest change of the lift per step [m].
LIFT_ITERS = 6
LIFT_MAX_STEP = 0.1
#: Below this height over its ankle joint a leg's stack keeps the section there (the foot's
#: section is left out: it reaches forward, and the smoothing of the sections spreads it up) [m].
ANKLE_ABOVE = 0.04
#: Smallest gap between the two legs' wrapped cloth where the thighs touch [m].
LEG_GAP = 0.03
#: A panel whose every point lies beyond this share of the shoulder's offset from the centre
#: plane (in its hint placement) is a sleeve, whichever way it faces.
SLEEVE_INNER = 0.6
#: ... and one beyond this share that reaches up past the middle of the upper arm is one too: a
#: wide sleeve's armhole comes nearer the centre plane (a torso's half reaches it, a skirt's gore
#: stays below; docs/decisions/053).
UPPER_SLEEVE_INNER = 0.25
#: ... and a sleeve's centre lies within this distance of its arm's bones (shoulder, elbow,
#: wrist) in its hint [m]: a wide skirt's side panels reach as far out as a sleeve under a
#: raised (T-pose) arm.
SLEEVE_REACH = 0.45
#: A stitched edge whose hint direction rises less than this share of its length is horizontal
#: (a shoulder seam between a front and a back, a waist seam between a bodice and a skirt).
HORIZONTAL_SLOPE = 0.6
#: The top of a sleeve's cap starts this far up the arm from the top of its armhole [m]
#: (measured on the base dress: 0 left it moving at 0.10 m/s after settling, 0.02 as before).
SLEEVE_CAP_IN = 0.02
#: A sleeve tube keeps the facing of its hint unless its caps then lie, on average, more than
#: SLEEVE_TURN_RATIO times (and SLEEVE_TURN_GAIN [m]) farther from the armhole points they are
#: sewn to than the best turn about the arm (tried every SLEEVE_TURN_STEP [deg]): a hint turned
#: against its stitches lets the sewing drag the sleeves through the armholes.
SLEEVE_TURN_RATIO = 2.0
SLEEVE_TURN_GAIN = 0.03
SLEEVE_TURN_STEP = 15
#: Seam vertices whose two copies are placed further apart than this start at their midpoint [m].
SEAM_MEET = 0.02
#: ... but only on a body with an upper arm less than this far below horizontal [deg]: the meeting
#: a T-pose (1 deg) and a raised arm (31 deg) need makes an A-pose's (48 deg) drape depend more on
#: its mesh.
MEET_ARM = 40.0
#: An upper arm less than this far below horizontal is raised [deg] (T-pose: 1; A-pose: 48).
ARM_RAISED = 30.0
#: How far out from the shoulder joint a raised arm's root joins the torso's stack [m].
ARM_ROOT = 0.05
#: Outline segments shorter than this many target edge lengths start about their length long.
TINY_EDGE = 0.3
#: A panel whose normal lies within this angle of the body's front axis faces front or back:
#: :func:`place_as_given` bends it round the body's vertical axis [deg].
FACING_DEG = 30.0
#: How far :func:`place_as_given` carries a point inside the body out along the horizontal from
#: the body's axis at most, in steps of CLEAR_STEP, and how far across its panel (rest distance)
#: the push fades out: at least CLEAR_FADE [m], and CLEAR_SLOPE times the push, so the panel
#: bends out stretched by under 3 % (sqrt(1 + 1/16)).
CLEAR_REACH = 0.3
CLEAR_STEP = 0.01
CLEAR_FADE = 0.06
CLEAR_SLOPE = 4.0
#: Height step of the cross-section tables [m].
_DY = 0.01


# -- geometry helpers --------------------------------------------------------------------------


def _ellipse_perimeter(a, b):
    """Ramanujan's approximation, arrays of semi-axes [m] -> perimeter [m]."""
    h = ((a - b) / (a + b)) ** 2
    return np.pi * (a + b) * (1 + 3 * h / (10 + np.sqrt(4 - 3 * h)))


def _ellipse_arc_table(a, b, n=257):
    """Cumulative arc length (N, n) [m] over phi in [0, 2 pi] (grid (n,)) on ellipses
    (a sin phi, b cos phi), a and b (N,) [m]."""
    phi = np.linspace(0.0, 2 * np.pi, n)
    seg = np.sqrt((a[:, None] * np.cos(phi)) ** 2 + (b[:, None] * np.sin(phi)) ** 2)  # (N, n) |dp/dphi|
    steps = 0.5 * (seg[:, 1:] + seg[:, :-1]) * np.diff(phi)
    return phi, np.concatenate([np.zeros((len(a), 1)), np.cumsum(steps, axis=1)], axis=1)


def _ellipse_at_arc(a, b, s0_phi, s):
    """Angle on ellipses (a, b) (each (N,)) reached after signed arc length ``s`` (N,) [m] from
    angle ``s0_phi`` (N,) [rad]; ellipse points are (a sin phi, b cos phi)."""
    phi, cum = _ellipse_arc_table(a, b)
    per = cum[:, -1]
    n = len(phi)
    r = np.arange(len(a))
    f = np.mod(s0_phi, 2 * np.pi) / (2 * np.pi) * (n - 1)
    i0 = np.clip(np.floor(f).astype(int), 0, n - 2)
    s_start = cum[r, i0] + (f - i0) * (cum[r, i0 + 1] - cum[r, i0])
    target = np.mod(s_start + s, per)
    j = np.clip((cum < target[:, None]).sum(axis=1) - 1, 0, n - 2)
    t = (target - cum[r, j]) / np.maximum(cum[r, j + 1] - cum[r, j], 1e-12)
    return phi[j] + t * (phi[j + 1] - phi[j])


def _section_table(points, ys, *, center=None):
    """Enclosing ellipse of the horizontal cross-sections of a point cloud.

    points: (M, 3) [m]; ys: (H,) heights [m]. Returns (cx, cz, a, b) each (H,) [m]: centre and
    semi-axes (x, z) of an ellipse containing every point within one table step of each height
    (empty heights copy the nearest filled one). center: optional (H, 2) fixed centres (x, z).
    """
    H = len(ys)
    out = np.full((H, 4), np.nan)
    idx = np.round((points[:, 1] - ys[0]) / _DY).astype(int)
    order = np.argsort(idx)
    idx_s = idx[order]
    for h in range(H):
        lo, hi = np.searchsorted(idx_s, [h - 1, h + 2])
        if hi - lo < 3:
            continue
        p = points[order[lo:hi]]
        if center is None:
            cx = 0.5 * (p[:, 0].max() + p[:, 0].min())
            cz = 0.5 * (p[:, 2].max() + p[:, 2].min())
        else:
            cx, cz = center[h]
        dx, dz = p[:, 0] - cx, p[:, 2] - cz
        a0 = max(np.abs(dx).max(), 0.02)
        b0 = max(np.abs(dz).max(), 0.02)
        s = np.sqrt(((dx / a0) ** 2 + (dz / b0) ** 2).max())  # >= 1: scale to enclose every point
        out[h] = (cx, cz, a0 * s, b0 * s)
    ok = ~np.isnan(out[:, 0])
    if not ok.any():
        raise InputError("the body has no vertices where the garment sits; is the body in metres and Y up?")
    fi = np.flatnonzero(ok)
    for k in range(4):
        out[:, k] = np.interp(np.arange(H), fi, out[fi, k])
    # Be generous: each height takes the largest semi-axes within +-2 steps; then smooth.
    for k in (2, 3):
        out[:, k] = _running_max(out[:, k], 2)
    ker = np.array([1.0, 2.0, 3.0, 2.0, 1.0]) / 9.0
    for k in range(4):
        out[:, k] = np.convolve(np.pad(out[:, k], 2, mode="edge"), ker, mode="valid")
    return [out[:, 0].copy(), out[:, 1].copy(), out[:, 2].copy(), out[:, 3].copy()]


def _width_at(poly_s, poly_y, ys):
    """Extent [min, max] along s of a closed polygon (given as (k,) arrays) at heights ys (H,).
    Returns (H, 2), NaN where the line misses the polygon."""
    s0, y0 = poly_s, poly_y
    s1, y1 = np.roll(poly_s, -1), np.roll(poly_y, -1)
    out = np.full((len(ys), 2), np.nan)
    for h, y in enumerate(ys):
        m = (np.minimum(y0, y1) <= y) & (np.maximum(y0, y1) >= y) & (y0 != y1)
        if not m.any():
            continue
        t = (y - y0[m]) / (y1[m] - y0[m])
        s = s0[m] + t * (s1[m] - s0[m])
        out[h] = (s.min(), s.max())
    return out


def _smoothstep(t):
    t = np.clip(t, 0.0, 1.0)
    return t * t * (3 - 2 * t)


# -- roles ------------------------------------------------------------------------------------


def _landmarks(body):
    sk = body.skeleton
    missing = sk.missing()
    if missing:
        raise InputError(
            f"the body's skeleton lacks joints {', '.join(missing)}; placement needs them (shared/FORMATS.md)"
        )
    J = {n: sk.position(n) for n in sk.names}
    parts = np.asarray(body.vertex_parts())
    v = np.asarray(body.verts, np.float64)
    cx = float(J["pelvis"][0])
    # Crotch: the lowest body point on the centre line above the knees.
    knee_y = max(J["left_knee"][1], J["right_knee"][1])
    m = (
        (np.abs(v[:, 0] - cx) < 0.012)
        & (v[:, 1] > knee_y)
        & (v[:, 1] < J["pelvis"][1])
        & np.isin(parts, ["torso", "left_leg", "right_leg"])
    )
    crotch_y = float(v[m, 1].min()) if m.any() else float(0.5 * (J["pelvis"][1] + knee_y))
    return J, parts, v, cx, crotch_y


def panel_roles(pattern, body) -> dict:
    """How each panel is placed: name -> ``"torso"``, ``"left_sleeve"``, ``"right_sleeve"``,
    ``"left_leg"``, ``"right_leg"`` or ``"free"`` (kept at its own placement), judged from the
    panel's 3D placement (translation/rotation) relative to the body's skeleton.

    A sleeve is a panel out to the side of its shoulder and above the crotch: either facing
    sideways (one panel round the arm, as unsew's base patterns draw it) or lying entirely
    beyond SLEEVE_INNER of the shoulder's offset from the centre plane (GarmentCode's front and
    back halves of a sleeve, facing front and back), or beyond UPPER_SLEEVE_INNER of it and
    reaching up past the middle of the upper arm (a wide sleeve's halves, whose armhole corner
    lies nearer the centre plane)."""
    J, _, _, cx, crotch_y = _landmarks(body)
    roles = {}
    for name in pattern.panel_order:
        p = pattern.panels[name]
        w = p.to_world(p.vertices)  # (k, 3) corners in the hint placement
        c = w.mean(axis=0)
        n = p.rotation_matrix()[:, 2]
        side = "left" if c[0] > cx else "right"
        sh = J[f"{side}_shoulder"]
        off_sh = abs(sh[0] - cx)
        out_by_arm = (
            c[1] > crotch_y + 0.1
            and abs(c[0] - cx) > 0.8 * off_sh
            and _arm_distance(c, J, side) < SLEEVE_REACH
        )
        if w[:, 1].min() > J["neck"][1] + 0.03 or c[1] > J["neck"][1]:
            roles[name] = "free"  # a collar, a hood
            continue
        inner = np.min(np.abs(w[:, 0] - cx)) / max(off_sh, 1e-6)  # its nearest to the centre plane
        upper_arm = w[:, 1].max() > 0.5 * (sh[1] + J[f"{side}_elbow"][1])  # up by the shoulder
        if out_by_arm and (
            (abs(n[0]) > 0.7 and c[1] > J[f"{side}_wrist"][1] - 0.1)
            or inner > SLEEVE_INNER
            or (upper_arm and inner > UPPER_SLEEVE_INNER)
        ):
            roles[name] = f"{side}_sleeve"
        elif (
            w[:, 1].min() < crotch_y - 0.08
            and abs(c[0] - cx) > 0.04
            and np.max(-np.sign(c[0] - cx) * (w[:, 0] - cx)) < 0.35 * np.ptp(w[:, 0])
        ):
            roles[name] = f"{side}_leg"
        elif abs(n[1]) < 0.7:
            roles[name] = "torso"
        else:
            roles[name] = "free"
    return roles


def _roles_on_body(pattern, body, J) -> dict:
    """:func:`panel_roles`, refusing a pattern whose own placement leaves every panel free, its
    centre above the body's neck (sized and placed for a much taller body: kept there, it drapes
    as a bag over the head)."""
    roles = panel_roles(pattern, body)
    if not roles or any(r != "free" for r in roles.values()):
        return roles
    low = min(float(pattern.panels[n].to_world(pattern.panels[n].vertices)[:, 1].mean()) for n in roles)
    if low > float(J["neck"][1]):
        raise InputError(
            f"the pattern's own placement puts every panel's centre above this body's neck (the "
            f"lowest at y = {low:.2f} m, the neck joint at {float(J['neck'][1]):.2f} m): it is sized "
            "and placed for a taller body; give the pattern made for this one"
        )
    return roles


def _arm_distance(p, J, side) -> float:
    """Distance [m] of a point p (3,) [m] from one arm's bones (shoulder-elbow, elbow-wrist)."""
    out = np.inf
    for a, b in ((f"{side}_shoulder", f"{side}_elbow"), (f"{side}_elbow", f"{side}_wrist")):
        a, b = np.asarray(J[a], np.float64), np.asarray(J[b], np.float64)
        t = np.clip(np.dot(p - a, b - a) / max(float(np.dot(b - a, b - a)), 1e-12), 0.0, 1.0)
        out = min(out, float(np.linalg.norm(p - (a + t * (b - a)))))
    return out


# -- placement -------------------------------------------------------------------------------


def place_garment(
    pattern,
    mesh,
    body,
    *,
    sdf=None,
    clearance: float = CLEARANCE,
    meet_seams: bool = True,
    force_meet: bool = False,
) -> np.ndarray:
    """Put the flat panels of ``pattern`` around ``body``: the start of the sewing phase.

    Args:
        pattern: unsew.pattern.model.Pattern whose panels carry a 3D placement hint
            (translation [m], rotation [deg]) telling side and height.
        mesh: its GarmentMesh (uv (Nu, 2) [m], uv_panel, panel_offsets, n_boundary, ...).
        body: unsew.body.body.Body with a skeleton (any body: nothing is hard-coded).
        sdf: optional BodySDF of ``body`` (built, disk-cached, when None) for the final push-out.
        clearance: gap between the body's cross-sections and the wrapped cloth [m].
        meet_seams: on a body with an arm raised above MEET_ARM, start seam vertices whose two
            copies are further apart than SEAM_MEET at their midpoint (see :func:`_meet_seams`);
            on any body, start outline stubs about their own length long (:func:`_close_stubs`).
        force_meet: meet the seam copies at their midpoint whatever the arms' pose (the retry of
            :func:`unsew.dress.dress` when a drape started without meeting exploded).

    Returns:
        x_unsewn: (Nu, 3) float64 [m], one 3D point per 2D rest vertex (seam copies apart).
    """
    uv = np.asarray(mesh.uv, np.float64)
    if len(uv) == 0:
        raise InputError("the garment mesh is empty; mesh the pattern first")
    J, parts, v, cx0, crotch_y = _landmarks(body)
    roles = _roles_on_body(pattern, body, J)
    ys = np.arange(v[:, 1].min() - 0.05, v[:, 1].max() + 0.3, _DY)  # (H,)
    x = np.asarray(mesh.uv_placed3d, np.float64).copy()  # free panels stay at their hint
    info = _panel_info(pattern, mesh, roles, x)
    stacks = _body_stacks(v, parts, J, cx0, crotch_y, ys, clearance)
    xb, ytop = _shoulder_line(v, parts, J, cx0)
    frame = _WrapFrame(stacks, ys, crotch_y, xb, ytop, clearance)
    x_wrap, lifts = _wrap_lifted(pattern, mesh, info, uv, frame, J)
    _put_wrapped(x, info, x_wrap, lifts)
    _put_sleeves(x, pattern, mesh, info, uv, J)
    if meet_seams and (force_meet or _arm_raised(J)):
        x = _meet_seams(x, mesh)
    if meet_seams:
        x = _close_stubs(x, mesh)
    return _push_out(x, body, sdf)


def hint_shift(pattern, mesh, body) -> float:
    """How far [m] (+y up) to move a pattern's own placement so that it sits on ``body`` as on the
    body its file was sized to: 0 unless the file's unlabelled shoulder seams (found by their
    structure alone, :func:`_hint_shoulders`) lie, as a median, more than HINT_SHIFT_TOL from
    HINT_SHOULDER_GAP below this body's shoulder line. unsew's own drafts, placed for their
    body and labelled, are never moved.

    pattern: Pattern whose panels carry their placement; mesh: its GarmentMesh; body: Body with a
    skeleton."""
    if not pattern.stitches:
        return 0.0  # no seams, no shoulders
    J, parts, v, cx, _ = _landmarks(body)
    reach = HINT_SHOULDER_REACH * 0.5 * abs(J["left_shoulder"][0] - J["right_shoulder"][0])
    q = _hint_shoulders(pattern, mesh, cx, reach)
    if q is None:
        return 0.0
    xb, ytop = _shoulder_line(v, parts, J, cx)
    dy = float(np.median(np.interp(q[:, 0], xb, ytop) - q[:, 1])) - HINT_SHOULDER_GAP
    return dy if abs(dy) > HINT_SHIFT_TOL else 0.0


def _hint_shoulders(pattern, mesh, cx: float, reach: float):
    """(k, 3) [m] own-placement points of a pattern's unlabelled shoulder seams, or None: seams
    between a panel facing front and one facing back, horizontal, each within SHOULDER_AT_TOP of
    its panel's top, within ``reach`` [m] of the centre plane ``x = cx`` on average, where the two
    panels are also sewn at their sides (:func:`_sewn_at_sides`). Every panel is taken for a
    torso panel: its role on this body is what a file sized to another body gets wrong."""
    if any("shoulder" in (e.label or "") for p in pattern.panels.values() for e in p.edges):
        return None  # labelled: unsew's own draft, placed for its body
    info = _panel_info(pattern, mesh, dict.fromkeys(mesh.panel_names, "torso"), np.asarray(mesh.uv_placed3d))
    sided = _sewn_at_sides(pattern, mesh, info)
    out = []
    for st in pattern.stitches:
        sides = (st.a, st.b)
        if frozenset(s.panel for s in sides) not in sided or not _front_to_back(info, sides):
            continue
        e = [_hint_edge(info, mesh, s) for s in sides]
        at_top = all(
            _is_horizontal(p) and p[:, 1].mean() > info[s.panel]["hint"][:, 1].max() - SHOULDER_AT_TOP
            for p, s in zip(e, sides)
        )
        if at_top and np.abs(e[0][:, 0] - cx).mean() < reach:
            out.append(e[0])
    return np.concatenate(out) if out else None


def place_as_given(pattern, mesh, body, *, sdf=None) -> np.ndarray:
    """The pattern's own 3D placement (each panel's translation and rotation, as a GarmentCode
    file sizes and places it for its body), with each panel facing front or back bent round the
    body's vertical axis (isometric across the panel: arc length = distance across it) at its own
    distance, or farther where that is needed to clear the body, and the points of the other
    panels inside the body carried out (:func:`_clear_of_body`). The start
    :func:`unsew.dress.dress` tries when the wrapped start (:func:`place_garment`) drapes unsound.

    pattern: Pattern whose panels carry their placement; mesh: its GarmentMesh; body: Body with
    a skeleton; sdf: its BodySDF (built when None). Returns x_unsewn (Nu, 3) float64 [m]."""
    if sdf is None:
        from unsew.body.sdf import BodySDF

        sdf = BodySDF.build(body)
    x = np.asarray(mesh.uv_placed3d, np.float64).copy()
    J, parts, v, cx, _ = _landmarks(body)
    torso = v[parts == "torso"] if (parts == "torso").any() else v
    axis = (cx, 0.5 * float(torso[:, 2].min() + torso[:, 2].max()))
    roles = _roles_on_body(pattern, body, J)
    bent = np.zeros(len(x), bool)
    for i, name in enumerate(mesh.panel_names):
        n = pattern.panels[name].rotation_matrix()[:, 2]
        if abs(n[2]) < np.cos(np.radians(FACING_DEG)) or roles[name].endswith("sleeve"):
            continue  # a sleeve (halves facing front and back too), a side piece: as placed
        a, b = int(mesh.panel_offsets[i]), int(mesh.panel_offsets[i + 1])
        for extra in np.arange(0.0, CLEAR_REACH + 1e-9, CLEAR_STEP):
            q = _bend_round(x[a:b], axis, extra)
            if not _near_body(sdf, q).any():
                break
        x[a:b], bent[a:b] = q, True
    x = _clear_of_body(x, mesh, sdf, axis, skip=bent)
    return _push_out(x, body, sdf)


def _bend_round(p, axis, extra: float) -> np.ndarray:
    """Points p (k, 3) [m] of a panel facing front or back bent round the vertical line through
    ``axis`` (x, z) [m] at their distance from it in z plus ``extra`` [m]: a point at ``s = x - cx``
    across goes to angle ``s / r`` on the circle of radius r (lengths across kept)."""
    cx, cz = axis
    dz = p[:, 2] - cz
    r = np.maximum(np.abs(dz), 0.05) + extra
    phi = (p[:, 0] - cx) / r
    out = p.copy()
    out[:, 0] = cx + r * np.sin(phi)
    out[:, 2] = cz + np.where(dz < 0, -1.0, 1.0) * r * np.cos(phi)
    return out


def _near_body(sdf, p) -> np.ndarray:
    """(k,) bool: the points p (k, 3) [m] closer than MIN_GAP to the body (or inside it)."""
    import torch

    with torch.no_grad():
        return sdf.query(torch.as_tensor(p, dtype=torch.float64))[0].numpy() < MIN_GAP


def _clear_of_body(x, mesh, sdf, axis, *, skip=None) -> np.ndarray:
    """x (Nu, 3) [m] with each point closer than MIN_GAP to the body carried out horizontally,
    away from the vertical line through ``axis`` (x, z) [m], by the first multiple of CLEAR_STEP
    (up to CLEAR_REACH) that clears it, and its panel's points within the fade (CLEAR_FADE, or
    CLEAR_SLOPE times the push; rest distance) by that push fading to 0, so the panel bends out
    smoothly; a point still inside stays. ``skip`` (Nu,) bool: points left as they are."""
    d = x[:, [0, 2]] - np.asarray(axis)
    dirn = np.zeros_like(x)
    dirn[:, [0, 2]] = d / np.maximum(np.linalg.norm(d, axis=1, keepdims=True), 1e-9)
    push = np.zeros(len(x))
    todo = np.flatnonzero(_near_body(sdf, x) & (True if skip is None else ~skip))
    moved = todo.copy()
    for _ in range(int(round(CLEAR_REACH / CLEAR_STEP))):
        if len(todo) == 0:
            break
        push[todo] += CLEAR_STEP
        todo = todo[_near_body(sdf, x[todo] + push[todo, None] * dirn[todo])]
    push[todo] = 0.0  # never cleared: left to the push-out and the sewing's contact
    out = np.zeros(len(x))
    uv, pan = np.asarray(mesh.uv, np.float64), np.asarray(mesh.uv_panel)
    for k in moved[push[moved] > 0]:
        same = np.flatnonzero(pan == pan[k])
        fade = max(CLEAR_FADE, CLEAR_SLOPE * push[k])
        w = np.clip(1.0 - np.linalg.norm(uv[same] - uv[k], axis=1) / fade, 0.0, 1.0)
        out[same] = np.maximum(out[same], push[k] * w)
    return x + out[:, None] * dirn


def _panel_info(pattern, mesh, roles, x) -> dict:
    """Per panel name: its slice of the uv vertices (``sl``), rotation matrix ``R`` (3, 3), the
    hint (``hint``, (k, 3) world positions [m] of its vertices in ``x``, (Nu, 3)), its boundary
    loop (``bl``, uv indices) and its placement role (``role``, see :func:`panel_roles`)."""
    info = {}
    for pi, name in enumerate(mesh.panel_names):
        p = pattern.panels[name]
        sl = slice(int(mesh.panel_offsets[pi]), int(mesh.panel_offsets[pi + 1]))
        info[name] = dict(
            sl=sl, R=p.rotation_matrix(), hint=x[sl].copy(), bl=mesh.boundary_loop(pi), role=roles[name]
        )
    return info


def _body_stacks(v, parts, J, cx0, crotch_y, ys, clearance) -> dict:
    """Stacks of horizontal ellipses around the torso and each leg: ``"torso"``,
    ``"left_leg"``, ``"right_leg"`` -> [cx, cz, a, b], each (H,) [m] at heights ``ys`` (H,).

    v: body vertices (V, 3) [m]; parts: (V,) part name of each; J: joint name -> (3,) [m];
    cx0: the pelvis's x [m]; crotch_y: crotch height [m]; clearance: cloth gap [m] (keeps the
    legs' stacks apart)."""
    torso_pts = v[np.isin(parts, ["torso", "left_leg", "right_leg"])]
    torso_pts = torso_pts[torso_pts[:, 1] < J["neck"][1]]
    # A raised arm (T-pose) leaves the torso at the height of the armholes: the torso's stack
    # takes in the arm's root there, so the armhole wraps round it instead of through it.
    roots = [_arm_root(v, parts, J, side, cx0) for side in ("left", "right")]
    torso_pts = np.concatenate([torso_pts] + [r for r in roots if r is not None])
    stacks = {"torso": _section_table(torso_pts, ys)}
    # Above the chest the torso does not narrow into the neck (what rises above the shoulders
    # folds over them, see _fold_over_shoulders); its depth follows the body.
    up = ys >= J["chest"][1]
    stacks["torso"][2][up] = np.maximum.accumulate(stacks["torso"][2][up])
    for side, sgn in (("left", 1.0), ("right", -1.0)):
        lp = v[
            np.isin(parts, ["torso", f"{side}_leg"])
            & ((v[:, 0] - cx0) * sgn > 0)
            & (v[:, 1] < crotch_y + 0.05)
        ]
        st = _section_table(lp, ys)
        # a trouser leg hangs on past the ankle as a tube: below it the stack keeps the
        # section above the ankle, not the foot's (a hem wrapped round the foot's long section
        # leaves its inseam open by the foot's length, and sewing pulls it through the foot)
        below = ys < float(J[f"{side}_ankle"][1]) + ANKLE_ABOVE
        if below.any() and not below.all():
            h = int(np.flatnonzero(~below)[0])
            for k in range(4):
                st[k][below] = st[k][h]
        stacks[f"{side}_leg"] = _keep_apart(st, cx0, sgn, clearance)
    return stacks


def _shoulder_line(v, parts, J, cx0):
    """The shoulder line: top of the torso (below the neck joint) per lateral position, over a
    raised arm's root (T-pose) where there is one: beyond the torso's side the torso's own top
    is the armpit, and a shoulder folded down to it would run through the arm. A column whose
    torso top lies below the chest joint is hip, not shoulder (hips wider than the armpits, as
    on a heavy older body): it takes the line of the shoulder columns beside it, else a lower
    garment's top, or a top's sides, lying out there would fold flat onto the hip's top.

    Returns (xb, ytop): lateral positions (101,) [m] every 1 cm over cx0 +- 0.5 m, and the
    torso's top height at each (101,) [m] (gaps interpolated)."""
    top = v[np.isin(parts, ["torso"]) & (v[:, 1] < J["neck"][1])]
    roots = [_arm_root(v, parts, J, side, cx0) for side in ("left", "right")]
    top = np.concatenate([top] + [r for r in roots if r is not None])
    xb = np.arange(-0.5, 0.5 + 1e-9, 0.01) + cx0
    ib = np.clip(np.round((top[:, 0] - xb[0]) / 0.01).astype(int), 0, len(xb) - 1)
    ytop = np.full(len(xb), -np.inf)
    np.maximum.at(ytop, ib, top[:, 1])
    ok = np.isfinite(ytop)
    if (ok & (ytop >= J["chest"][1])).any():
        ok &= ytop >= J["chest"][1]
    ytop = np.interp(xb, xb[ok], ytop[ok])
    return xb, ytop


def _stack_coords(d, uv):
    """(along, across, phi0, c_hint) of a panel's vertices for wrapping on a stack: height
    along the panel's up direction (k,) [m], coordinate across it (k,) [m], the angle of its
    normal around the vertical [rad] and the centre of its hint (3,) [m].

    d: the panel's entry of :func:`_panel_info`; uv: all rest positions (Nu, 2) [m]."""
    R = d["R"]
    u = uv[d["sl"]]
    a2 = R[:, :2].T @ np.array([0.0, 1.0, 0.0])  # panel-frame direction that points up
    if np.linalg.norm(a2) < 1e-6:
        a2 = np.array([0.0, 1.0])
    a2 = a2 / np.linalg.norm(a2)
    b2 = np.array([a2[1], -a2[0]])
    nrm = R[:, 2]
    phi0 = np.arctan2(nrm[0], nrm[2])
    c_uv = u.mean(axis=0)
    c_hint = d["hint"].mean(axis=0)
    along = (u - c_uv) @ a2 + c_hint[1]
    across = (u - c_uv) @ b2
    return along, across, phi0, c_hint


def _grow_to_girth(a, b, need):
    """Semi-axes (a, b), each (k,) [m], grown to the perimeter ``need`` (k,) [m] where the
    ellipse is shorter: first in depth up to a circle (the arms limit the width of the torso),
    beyond that into a wider circle. Returns the new (a, b)."""
    grow = need > _ellipse_perimeter(a, b)
    bmax = np.maximum(a, b)
    lo, hi = b.copy(), bmax.copy()
    for _ in range(30):
        mid = 0.5 * (lo + hi)
        big = _ellipse_perimeter(a, mid) > need
        hi = np.where(big, mid, hi)
        lo = np.where(big, lo, mid)
    circle = need > _ellipse_perimeter(a, bmax)
    r = need / (2 * np.pi)
    b = np.where(grow, np.where(circle, np.maximum(r, b), hi), b)
    a = np.where(grow & circle, np.maximum(r, a), a)
    return a, b


def _wrap_stack(stack, y, S, phi_c, ys, clearance, *, perim=None):
    """Points (k, 3) [m] on a stack ([cx, cz, a, b] over heights ``ys`` (H,)) at heights y (k,)
    [m] with arc coordinates S (k,) [m] measured from angle phi_c [rad], ``clearance`` [m]
    outside the body's sections; ``perim`` (H,) [m]: the garment's girth to grow to."""
    cx, cz, a, b = (np.interp(y, ys, t) for t in stack)
    a = a + clearance
    b = b + clearance
    if perim is not None:
        a, b = _grow_to_girth(a, b, np.interp(y, ys, perim))
    phi = _ellipse_at_arc(a, b, np.broadcast_to(phi_c, a.shape).astype(np.float64), S)
    return np.stack([cx + a * np.sin(phi), y, cz + b * np.cos(phi)], axis=1)


@dataclass(frozen=True)
class _WrapFrame:
    """The body as the torso and leg panels are wrapped on it: the cross-section ``stacks``
    (name -> per-height arrays at the heights ``ys`` (H,) [m], :func:`_body_stacks`), the
    crotch height ``crotch_y`` [m], the shoulder line ``ytop`` [m] over ``xb`` [m]
    (:func:`_shoulder_line`) and the ``clearance`` [m] kept from the body."""

    stacks: dict
    ys: np.ndarray
    crotch_y: float
    xb: np.ndarray
    ytop: np.ndarray
    clearance: float


def _wrap_lifted(pattern, mesh, info, uv, frame: _WrapFrame, J):
    """Torso and leg panels wrapped on their stacks at their solved heights.

    Lifts [m]: a top hangs from its shoulder seams, so its front and back panels are raised
    until what rises above the shoulder line folds over it to the ridge, where the two
    shoulder edges meet (the panels' hint puts them at the shoulder tip, below the ridge).
    The missing run falls by more than the lift that removes it where the raised panel wraps
    a shallower part of the torso (a front over the chest: about -2.4 per m), so a plain
    fixed-point step overshoots and oscillates; secant steps on each panel's residual converge.
    A garment without shoulder seams gets :func:`_lower_garment_lifts`.

    Returns (name -> (k, 3) wrapped positions [m], name -> lift [m])."""
    lifts = {name: 0.0 for name in info}
    shoulder_edges = _shoulder_edges(pattern, mesh, info, above=float(J["chest"][1]))
    links = _horizontal_links(pattern, mesh, info)
    if not shoulder_edges:
        _lower_garment_lifts(lifts, info, links, J, frame.crotch_y)
    hist: dict = {name: [] for name in shoulder_edges}  # (lift, residual) per iteration
    folds: dict = {}  # name -> positions before the shoulder fold; set by the first pass (it == 0)
    for it in range(LIFT_ITERS + 1 if shoulder_edges else 1):
        if it:
            for name, idx in shoulder_edges.items():
                r = _shoulder_lift(
                    folds[name],
                    idx - info[name]["sl"].start,
                    frame.xb,
                    frame.ytop,
                    frame.clearance,
                    frame.stacks["torso"],
                    frame.ys,
                )
                hist[name].append((lifts[name], r))
                lifts[name] = _secant_step(hist[name])
            _propagate_lifts(lifts, links, list(shoulder_edges))
        x_wrap, folds = _wrap_all(info, uv, lifts, frame)
    return x_wrap, lifts


def _lower_garment_lifts(lifts, info, links, J, crotch_y) -> None:
    """Lifts [m] (in place) of a lower garment (or anything not hanging from shoulders): kept
    at its hint height when its top lies on this body's torso between the crotch and the
    chest, else its top goes to the body's waist (the spine joint); panels sewn below or above
    it by horizontal seams (``links``) follow it."""
    wrapped = [n for n, d in info.items() if d["role"] in ("torso", "left_leg", "right_leg")]
    if not wrapped:
        return
    top_name = max(wrapped, key=lambda n: float(info[n]["hint"][:, 1].max()))
    top = float(info[top_name]["hint"][:, 1].max())
    fits = crotch_y + 0.1 <= top <= float(J["chest"][1])
    base = 0.0 if fits else float(J["spine"][1]) - top
    for n in wrapped:
        lifts[n] = base
    _propagate_lifts(lifts, links, [top_name])


def _put_wrapped(x, info, x_wrap, lifts) -> None:
    """Write the wrapped panels ``x_wrap`` into ``x`` (Nu, 3) [m] (in place); free panels (a
    hood, a collar) follow the garment up or down by the mean lift."""
    moved = [lifts[n] for n in x_wrap]
    for name, d in info.items():
        if name in x_wrap:
            x[d["sl"]] = x_wrap[name]
        elif d["role"] == "free" and moved:
            x[d["sl"]] = d["hint"] + np.array([0.0, float(np.mean(moved)), 0.0])


def _put_sleeves(x, pattern, mesh, info, uv, J) -> None:
    """Sleeves into ``x`` (Nu, 3) [m] (in place): a tube round their arm, as wide as all panels
    of that arm side by side, moved along the arm until the top of the cap sits SLEEVE_CAP_IN
    inside the top of the armhole it is sewn to (the armhole as already placed in ``x``)."""
    caps = _sleeve_caps(pattern, mesh, info)
    for side in ("left", "right"):
        names = [n for n, d in info.items() if d["role"] == f"{side}_sleeve"]
        if not names:
            continue
        axes = {n: _sleeve_axis(uv[info[n]["sl"]], info[n], caps.get(n), J, side) for n in names}
        shifts = {}
        for n in names:
            d, cap = info[n], caps.get(n)
            if cap is not None and len(cap[1]):
                top = _armhole_top(x[cap[1]], J, side)
                shifts[n] = top - SLEEVE_CAP_IN - float(np.min(axes[n][0][cap[0] - d["sl"].start]))
        capped = list(shifts)
        _follow_sewn_sleeves(shifts, axes, names, info, mesh)
        # the tube goes round the arm once: the panels with a cap side by side (a cuff below
        # them is as wide again)
        width = sum(
            float(np.ptp(ax[1][info[n]["bl"] - info[n]["sl"].start]))
            for n, ax in axes.items()
            if n in capped or not capped
        )
        radius = max(width / (2 * np.pi), 0.03)

        def wrapped(turn):
            return {
                n: _wrap_sleeve(*axes[n], info[n], side, J, radius=radius, shift=shifts.get(n), turn=turn)
                for n in names
            }

        turn = _sleeve_turn(wrapped, x, caps, info, names)
        for n, xs in wrapped(turn).items():
            x[info[n]["sl"]] = xs


def _follow_sewn_sleeves(shifts, axes, names, info, mesh) -> None:
    """Shifts down the arm [m] (in place) of an arm's sleeve panels without a cap (a cuff): each
    goes where its edge sewn to an already shifted panel of the same arm meets that panel's
    edge (the mean positions along the arm equal), panel after panel down a chain of them.
    ``axes``: name -> (along, across) of :func:`_sleeve_axis`."""
    sp = np.asarray(mesh.seam_pairs, np.int64).reshape(-1, 2)
    part = np.asarray(mesh.uv_panel)
    pid = {n: mesh.panel_names.index(n) for n in names}
    todo = [n for n in names if n not in shifts]
    while todo:
        for n in todo:
            for m in [m for m in names if m in shifts]:
                pairs = [
                    (a, b)
                    for i, j in sp
                    for a, b in ((i, j), (j, i))
                    if part[a] == pid[n] and part[b] == pid[m]
                ]
                if pairs:
                    a, b = np.asarray(pairs).T
                    t_m = axes[m][0][b - info[m]["sl"].start] + shifts[m]
                    shifts[n] = float(np.mean(t_m) - np.mean(axes[n][0][a - info[n]["sl"].start]))
                    break
            if n in shifts:
                todo.remove(n)
                break
        else:
            return  # the rest are sewn to no shifted panel: they keep their default start


def _sleeve_turn(wrapped, x, caps, info, names) -> float:
    """The turn [rad] about the arm for one arm's sleeve panels: 0 (the hint's facing) unless
    their caps would lie far nearer the armhole points they are sewn to turned (see
    SLEEVE_TURN_RATIO). ``wrapped(turn)`` -> panel name -> (k, 3) wrapped positions [m]."""
    capped = [n for n in names if n in caps and len(caps[n][1])]
    if not capped:
        return 0.0

    def gap(turn):
        ws = wrapped(turn)
        d = [np.linalg.norm(ws[n][caps[n][0] - info[n]["sl"].start] - x[caps[n][1]], axis=1) for n in capped]
        return float(np.concatenate(d).mean())

    turns = np.radians(np.arange(0, 360, SLEEVE_TURN_STEP))
    gaps = np.array([gap(t) for t in turns])
    k = int(np.argmin(gaps))
    if gaps[0] > SLEEVE_TURN_RATIO * gaps[k] and gaps[0] - gaps[k] > SLEEVE_TURN_GAIN:
        return float(turns[k])
    return 0.0


def _meet_seams(x, mesh):
    """Start the two copies of every seam vertex further apart than SEAM_MEET at their
    midpoint (the push-out that follows lifts any midpoint that lands in the body). Seam
    springs closing a gap of several cm in one step drag whole panels; where a limb is in
    the way (a T-pose's sleeve pulled to the armpit) the cloth tore over it (stretch 4-6).
    Only the seam vertices move, so the rows beside them start bent; place_garment calls this
    only where an arm is raised (MEET_ARM)."""
    sp = np.asarray(mesh.seam_pairs)
    if len(sp) == 0:
        return x
    gap = np.linalg.norm(x[sp[:, 0]] - x[sp[:, 1]], axis=1)
    far = sp[gap > SEAM_MEET]
    x = x.copy()
    mid = 0.5 * (x[far[:, 0]] + x[far[:, 1]])  # (k, 3)
    x[far[:, 0]] = mid
    x[far[:, 1]] = mid
    return x


def _close_stubs(x, mesh):
    """Bring the ends of outline stubs shorter than TINY_EDGE edge lengths (GarmentCode leaves
    1-5 mm segments where an interface was split) to within the stub's length of each other:
    every copy of such an end moves to its sewn vertex's mean, pulled towards the stub cluster's
    mean until it lies within the stub's length of it (not onto it: a zero-length edge makes
    the step's matrix singular). Placed cm apart, a 1 mm stub starts stretched 30 times."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    xu = np.asarray(mesh.x_of_u)
    n = int(mesh.n_x)
    stubs, lens = [], []
    for p in range(len(mesh.panel_names)):
        bl = mesh.boundary_loop(p)
        seg = np.stack([bl, np.roll(bl, -1)], axis=1)
        L = np.linalg.norm(mesh.uv[seg[:, 0]] - mesh.uv[seg[:, 1]], axis=1)
        short = L < TINY_EDGE * mesh.edge_length
        stubs.append(xu[seg[short]])
        lens.append(L[short])
    e = np.concatenate(stubs).reshape(-1, 2)
    if len(e) == 0:
        return x
    cnt = np.bincount(xu, minlength=n).astype(np.float64)
    m = (
        np.stack([np.bincount(xu, weights=x[:, k], minlength=n) for k in range(3)], axis=1)
        / np.maximum(cnt, 1.0)[:, None]
    )
    g = coo_matrix((np.ones(len(e)), (e[:, 0], e[:, 1])), shape=(n, n))
    _, lab = connected_components(g, directed=False)
    c_cnt = np.bincount(lab).astype(np.float64)
    M = np.stack([np.bincount(lab, weights=m[:, k]) for k in range(3)], axis=1) / c_cnt[:, None]
    r = np.zeros(len(c_cnt))
    np.maximum.at(r, lab[e[:, 0]], np.concatenate(lens))
    d = m - M[lab]
    dn = np.linalg.norm(d, axis=1)
    shrink = (c_cnt[lab] > 1) & (dn > r[lab])
    m[shrink] = M[lab[shrink]] + d[shrink] * (r[lab[shrink]] / dn[shrink])[:, None]
    x = x.copy()
    sel = shrink[xu]
    x[sel] = m[xu[sel]]
    return x


def meets_seams(body) -> bool:
    """Whether :func:`place_garment` starts seam copies at their midpoint on ``body`` by default:
    an upper arm raised above MEET_ARM below horizontal."""
    sk = body.skeleton
    return _arm_raised({n: sk.position(n) for n in sk.names})


def _arm_raised(J) -> bool:
    return min(_arm_drop(J, side) for side in ("left", "right")) < MEET_ARM


def _arm_drop(J, side) -> float:
    """How far one upper arm (shoulder -> elbow) hangs below horizontal [deg] (negative: above)."""
    _, seg, L = _arm_frame(J, side)
    return float(np.degrees(np.arcsin(np.clip(-seg[0][1] / L[0], -1.0, 1.0))))


def _arm_root(v, parts, J, side, cx):
    """Vertices (k, 3) [m] of a raised arm's root (within ARM_ROOT of its shoulder joint
    sideways), or None when the upper arm hangs more than ARM_RAISED below horizontal."""
    A, _, _ = _arm_frame(J, side)
    if _arm_drop(J, side) > ARM_RAISED:
        return None
    m = (parts == f"{side}_arm") & (np.abs(v[:, 0] - cx) < abs(A[0][0] - cx) + ARM_ROOT)
    return v[m]


def _secant_step(hist) -> float:
    """Next lift [m] from the (lift, residual) history of one panel: a secant step through the
    last two points (residual: the lift still missing), a plain step when there is one point or
    the slope is not negative. Steps are limited to LIFT_MAX_STEP."""
    l1, r1 = hist[-1]
    step = r1
    if len(hist) > 1:
        l0, r0 = hist[-2]
        slope = (r1 - r0) / (l1 - l0) if abs(l1 - l0) > 1e-9 else 0.0
        if slope < -1e-3:
            step = -r1 / slope
    return l1 + float(np.clip(step, -LIFT_MAX_STEP, LIFT_MAX_STEP))


def _keep_apart(stack, cx0, sgn, clearance):
    """A leg's stack of ellipses kept on its own side of the centre plane x = cx0 (sgn +1: the
    left leg at x > cx0): where the thighs touch, the inner side of the wrapped cloth stays
    LEG_GAP / 2 from the plane (the outer side is kept; the push-out lifts what is inside)."""
    cx, cz, a, b = (t.copy() for t in stack)
    outer = cx + sgn * a
    inner_lim = cx0 + sgn * (0.5 * LEG_GAP + clearance)
    m = sgn * (cx - a * sgn - inner_lim) < 0  # the inner side crosses the limit
    a_new = np.maximum(0.5 * sgn * (outer - inner_lim), 0.02)
    a = np.where(m, a_new, a)
    cx = np.where(m, outer - sgn * a, cx)
    return [cx, cz, a, b]


def _shoulder_edges(pattern, mesh, info, *, above: float = -np.inf) -> dict:
    """Torso panels with stitched shoulder edges -> uv indices of those edges' vertices.

    A shoulder edge is labelled so (unsew's base patterns) or, unlabelled (GarmentCode's
    files), a horizontal seam (:func:`_is_horizontal` in the hint placement) between a torso
    panel facing front and one facing back, in the upper half of both and higher than
    ``above`` [m] (the body's chest: a circle skirt laid out flat has horizontal side seams at
    its waist), or within SHOULDER_AT_TOP of the torso panels' top where the two panels are
    also sewn at their sides (a top sized to a shorter body has its shoulder seams below this
    body's chest; a flat-laid circle skirt's halves meet only at its horizontal seams)."""
    out = {}
    top = max((d["hint"][:, 1].max() for d in info.values() if d["role"] == "torso"), default=np.inf)
    sided = _sewn_at_sides(pattern, mesh, info)
    for st in pattern.stitches:
        sides = (st.a, st.b)
        labelled = any("shoulder" in (pattern.panels[s.panel].edges[s.edge].label or "") for s in sides)
        if not labelled:
            if not _front_to_back(info, sides):
                continue
            low = min(above, top - SHOULDER_AT_TOP) if frozenset(s.panel for s in sides) in sided else above
            ok = True
            for s in sides:
                h, e = info[s.panel]["hint"], _hint_edge(info, mesh, s)
                ok &= _is_horizontal(e) and e[:, 1].mean() > max(h[:, 1].min() + 0.5 * np.ptp(h[:, 1]), low)
            if not ok:
                continue
        for side in sides:
            if info[side.panel]["role"] == "torso":
                idx = np.asarray(mesh.edge_verts[(side.panel, side.edge)])
                out[side.panel] = np.union1d(out.get(side.panel, np.zeros(0, np.int64)), idx)
    return out


def _front_to_back(info, sides) -> bool:
    """Whether a stitch's two sides lie on torso panels, one facing front and one back."""
    if any(info[s.panel]["role"] != "torso" for s in sides):
        return False
    nz = [info[s.panel]["R"][2, 2] for s in sides]
    return bool(nz[0] * nz[1] < 0 and min(abs(z) for z in nz) > 0.5)


def _hint_edge(info, mesh, side) -> np.ndarray:
    """(k, 3) [m] hint positions of a stitch side's edge vertices."""
    d = info[side.panel]
    return d["hint"][np.asarray(mesh.edge_verts[(side.panel, side.edge)]) - d["sl"].start]


def _sewn_at_sides(pattern, mesh, info) -> set:
    """Pairs (frozensets of panel names) of front and back torso panels joined by a seam that is
    not horizontal in the hint placement: a bodice's halves at its side seams."""
    return {
        frozenset(s.panel for s in (st.a, st.b))
        for st in pattern.stitches
        if _front_to_back(info, (st.a, st.b)) and not _is_horizontal(_hint_edge(info, mesh, st.a))
    }


def _shoulder_lift(p, idx, xb, ytop, clearance, stack, ys) -> float:
    """How much higher [m] a panel must sit for its shoulder-edge vertices (``p[idx]``, wrapped
    positions before the fold over the shoulders) to fold to SHOULDER_MEET from the body's
    centre plane: the run still missing, averaged over the edge."""
    q = p[idx]
    y_line = np.interp(q[:, 0], xb, ytop) + clearance
    cz = np.interp(y_line, ys, stack[1])
    run = np.abs(q[:, 2] - cz) - SHOULDER_MEET
    return float(np.mean(run - (q[:, 1] - y_line)))


def _needed_widths(info, uv, lifts, frame: _WrapFrame) -> tuple[dict, dict]:
    """The widths [m] needed around each stack at each height (front + back panels side by
    side; stack name -> (H,)), and per torso or leg panel its stack coordinates raised by its
    lift (name -> (along, across, phi0, c_hint, extent))."""
    ys, crotch_y = frame.ys, frame.crotch_y
    need = {k: np.zeros(len(ys)) for k in frame.stacks}
    coords = {}
    for name, d in info.items():
        role = d["role"]
        if role not in ("torso", "left_leg", "right_leg"):
            continue
        along, across, phi0, c_hint = _stack_coords(d, uv)
        along = along + lifts[name]
        c_hint = c_hint + np.array([0.0, lifts[name], 0.0])
        bl = d["bl"] - d["sl"].start
        ext = _width_at(across[bl], along[bl], ys)
        coords[name] = (along, across, phi0, c_hint, ext)
        w = np.nan_to_num(ext[:, 1] - ext[:, 0])
        if role == "torso":
            need["torso"] += w
        else:
            need["torso"] += np.where(ys > crotch_y, w, 0.0)
            need[role] += np.where(ys < crotch_y + CROTCH_BLEND, w, 0.0)

    # A curved hem's horizontal slices are narrower than the cloth above them: each height
    # takes the largest girth found up to NEED_WINDOW above it.
    k = int(round(NEED_WINDOW / _DY))
    for key in need:
        p = np.pad(need[key], (0, k), mode="edge")
        need[key] = np.max(np.stack([p[i : i + len(ys)] for i in range(k + 1)]), axis=0)
    return need, coords


def _wrap_leg(d, coords, p_torso, need, frame: _WrapFrame) -> np.ndarray:
    """A leg panel wrapped on its leg's stack, its inseam edge (the side towards the other leg)
    on the leg's innermost line, so the front's and back's inseams meet there and any slack
    goes to the outseam; blended into its torso wrap ``p_torso`` (k, 3) [m] about the crotch."""
    along, across, _, _, ext = coords
    role, ys, crotch_y = d["role"], frame.ys, frame.crotch_y
    sgn = 1.0 if role == "left_leg" else -1.0
    R = d["R"]
    a2 = R[:, :2].T @ np.array([0.0, 1.0, 0.0])
    a2 = a2 / max(np.linalg.norm(a2), 1e-9)
    b2 = np.array([a2[1], -a2[0]])
    inward = -np.sign((R[:, :2] @ b2)[0]) * sgn  # +1: the across coordinate grows inwards
    ok = np.flatnonzero(~np.isnan(ext[:, 0]))
    if not len(ok):  # wholly below the body's heights (a hem laid out under the feet)
        return p_torso
    edge = np.interp(along, ys[ok], ext[ok, 1] if inward > 0 else ext[ok, 0])
    phi_in = -0.5 * np.pi * sgn
    p_leg = _wrap_stack(
        frame.stacks[role], along, across - edge, phi_in, ys, frame.clearance, perim=need[role]
    )
    w = _smoothstep((crotch_y + CROTCH_BLEND - along) / (2 * CROTCH_BLEND))[:, None]
    return w * p_leg + (1 - w) * p_torso


def _wrap_all(info, uv, lifts, frame: _WrapFrame):
    """Torso and leg panels wrapped on their stacks, each raised by ``lifts[name]`` [m].
    Returns (name -> (k, 3) positions, name -> (k, 3) positions before the shoulder fold)."""
    need, coords = _needed_widths(info, uv, lifts, frame)
    ys, clearance = frame.ys, frame.clearance
    out, folds = {}, {}
    for name, (along, across, phi0, c_hint, ext) in coords.items():
        d = info[name]
        st = frame.stacks["torso"]
        axis_x = np.interp(c_hint[1], ys, st[0])
        axis_z = np.interp(c_hint[1], ys, st[1])
        t_hat = np.array([np.cos(phi0), 0.0, -np.sin(phi0)])
        S_c = t_hat @ (c_hint - np.array([axis_x, 0.0, axis_z]))
        p_flat = _wrap_stack(st, along, across + S_c, phi0, ys, clearance, perim=need["torso"])
        folds[name] = p_flat
        p_torso = _fold_over_shoulders(p_flat, phi0, frame.xb, frame.ytop, clearance, st, ys)
        if d["role"] == "torso":
            out[name] = p_torso
        else:
            out[name] = _wrap_leg(d, coords[name], p_torso, need, frame)
    return out, folds


def _fold_over_shoulders(p, phi0, xb, ytop, clearance, stack, ys):
    """Fold what rises above the shoulder line horizontally towards the body's centre plane
    (isometric: the excess height becomes a horizontal run)."""
    y_line = np.interp(p[:, 0], xb, ytop) + clearance
    e = p[:, 1] - y_line
    m = e > 0
    if not m.any():
        return p
    q = p.copy()
    cz = np.interp(y_line[m], ys, stack[1])
    dirz = -np.sign(np.cos(phi0)) if abs(np.cos(phi0)) > 1e-3 else 0.0
    if dirz == 0.0:
        return p
    z_new = q[m, 2] + dirz * e[m]
    # never cross the centre plane (front and back roofs meet there)
    lim = cz - dirz * 0.5 * SHOULDER_MEET
    z_new = np.maximum(z_new, lim) if dirz < 0 else np.minimum(z_new, lim)
    q[m, 1] = y_line[m]
    q[m, 2] = z_new
    return q


def _arm_frame(J, side):
    """Joints (3, 3) shoulder, elbow, wrist [m] of one arm, its segments (2, 3) and lengths (2,)."""
    A = np.stack([J[f"{side}_shoulder"], J[f"{side}_elbow"], J[f"{side}_wrist"]])
    seg = np.diff(A, axis=0)
    return A, seg, np.linalg.norm(seg, axis=1)


def _sleeve_axis(u, d, cap, J, side):
    """(along, across) [m] of a sleeve panel's vertices u (k, 2): along runs down the arm from
    the panel's centre, across round it (the panel's frame turned so that across = along x z).

    The direction down the arm is, in the panel's own frame, from its cap (the edges sewn to
    the torso, ``cap`` = (uv indices, indices of the torso vertices they are sewn to)) to its
    centre, snapped to the panel's nearest principal axis when within 35 degrees (sleeves are
    drawn along an axis); without a cap, the arm's direction seen through the hint placement."""
    R = d["R"]
    c_uv = u.mean(axis=0)
    a2 = None
    if cap is not None and len(cap[0]):
        v = c_uv - u[cap[0] - d["sl"].start].mean(axis=0)
        if np.linalg.norm(v) > 1e-6:
            a2 = v / np.linalg.norm(v)
            w, V = np.linalg.eigh(np.cov((u - c_uv).T))
            for k in range(2):
                ax = V[:, k] * np.sign(V[:, k] @ a2)
                if ax @ a2 > np.cos(np.radians(35.0)):
                    a2 = ax
    if a2 is None:
        _, seg, L = _arm_frame(J, side)
        a2 = R[:, :2].T @ (seg[0] / L[0])
        a2 = a2 / max(np.linalg.norm(a2), 1e-9)
    b2 = np.array([a2[1], -a2[0]])
    return (u - c_uv) @ a2, (u - c_uv) @ b2


def _armhole_top(p, J, side) -> float:
    """Position [m] along the arm line (from the shoulder joint, along shoulder -> elbow) of
    the armhole point p (k, 3) nearest the neck: the top of the armhole."""
    A, seg, L = _arm_frame(J, side)
    return float(np.min((p - A[0]) @ (seg[0] / L[0])))


def _wrap_sleeve(along, across, d, side, J, *, radius, shift=None, turn=0.0):
    """A sleeve panel wrapped onto a tube of ``radius`` [m] round its arm's shoulder-elbow-wrist
    line. along/across (k,) [m]: the panel's coordinates (:func:`_sleeve_axis`); the point
    along = 0 goes ``shift`` [m] down the arm from the shoulder joint (default: the cap's top
    3 cm inside the shoulder). The middle of the panel faces where its placement normal points,
    off the arm's axis (a one-piece sleeve: up and out; a front half: to the front), turned
    ``turn`` [rad] about the arm from there."""
    A, seg, L = _arm_frame(J, side)
    d0 = seg[0] / L[0]
    R = d["R"]
    t = along - along.min() - 0.03 if shift is None else along + shift
    cum = np.concatenate([[0.0], np.cumsum(L)])

    def axis_at(tt):
        k = np.clip(np.searchsorted(cum, tt) - 1, 0, len(L) - 1)
        return A[k] + (tt - cum[k])[:, None] * (seg[k] / L[k, None]), seg[k] / L[k, None]

    P, D = axis_at(t)
    n = R[:, 2]
    e1 = n - (n @ d0) * d0
    if np.linalg.norm(e1) < 1e-6:
        e1 = np.cross(d0, [0.0, 0.0, 1.0])
    e1 = e1 / np.linalg.norm(e1)
    e1 = np.cos(turn) * e1 + np.sin(turn) * np.cross(d0, e1)
    E1 = e1 - (np.einsum("ij,j->i", D, e1))[:, None] * D
    E1 /= np.linalg.norm(E1, axis=1, keepdims=True)
    E2 = np.cross(D, E1)
    th = across / radius
    return P + radius * (np.cos(th)[:, None] * E1 + np.sin(th)[:, None] * E2)


def _sleeve_caps(pattern, mesh, info) -> dict:
    """Sleeve panel -> (uv indices of its edges sewn to torso panels, the torso uv indices they
    are sewn to), both (k,) int64."""
    sp = np.asarray(mesh.seam_pairs)
    part = np.asarray(mesh.uv_panel)
    names = mesh.panel_names
    out: dict = {}
    for i, j in sp:
        for a, b in ((i, j), (j, i)):
            na, nb = names[part[a]], names[part[b]]
            if info[na]["role"].endswith("_sleeve") and info[nb]["role"] == "torso":
                out.setdefault(na, ([], []))
                out[na][0].append(int(a))
                out[na][1].append(int(b))
    return {k: (np.asarray(v[0], np.int64), np.asarray(v[1], np.int64)) for k, v in out.items()}


def _horizontal_links(pattern, mesh, info) -> list:
    """Horizontal seams between wrapped panels (a bodice's waist to a skirt, a waistband to
    trousers): (a, b, dy) with dy [m] the hint height of a's edge over b's, so that b sits
    right when ``lift[b] = lift[a] + dy``. Both directions are listed."""
    wrapped = ("torso", "left_leg", "right_leg")
    out = []
    for st in pattern.stitches:
        a, b = st.a.panel, st.b.panel
        if a == b or info[a]["role"] not in wrapped or info[b]["role"] not in wrapped:
            continue
        ya, yb = [
            info[s.panel]["hint"][np.asarray(mesh.edge_verts[(s.panel, s.edge)]) - info[s.panel]["sl"].start]
            for s in (st.a, st.b)
        ]
        if not all(_is_horizontal(y) for y in (ya, yb)):
            continue
        dy = float(ya[:, 1].mean() - yb[:, 1].mean())
        out += [(a, b, dy), (b, a, -dy)]
    return out


def _is_horizontal(p) -> bool:
    """Whether a polyline p (k, 3) [m] runs sideways: its chord rises less than HORIZONTAL_SLOPE
    of its length."""
    ch = p[-1] - p[0]
    return abs(ch[1]) < HORIZONTAL_SLOPE * max(np.linalg.norm(ch), 1e-9)


def _propagate_lifts(lifts, links, roots) -> None:
    """Give every panel reachable from ``roots`` through horizontal seams (``links`` of
    :func:`_horizontal_links`) the lift that puts its seam at the height of the one above or
    below it (breadth first, in place); roots keep theirs."""
    seen = set(roots)
    queue = list(roots)
    while queue:
        a = queue.pop(0)
        for p, q, dy in links:
            if p == a and q not in seen:
                lifts[q] = lifts[a] + dy
                seen.add(q)
                queue.append(q)


def _running_max(a, k):
    """Largest value within +-k entries (edges padded)."""
    p = np.pad(a, k, mode="edge")
    return np.max(np.stack([p[i : i + len(a)] for i in range(2 * k + 1)]), axis=0)


def _push_out(x, body, sdf):
    """Move points closer than MIN_GAP to the body (or inside, by at most MAX_PUSH deep) out
    along the SDF normal."""
    import torch

    if sdf is None:
        from unsew.body.sdf import BodySDF

        sdf = BodySDF.build(body)
    xt = torch.as_tensor(x, dtype=torch.float64)
    for _ in range(3):
        with torch.no_grad():
            dd, nn = sdf.query(xt)
        m = (dd < MIN_GAP) & (dd > -MAX_PUSH)
        if not bool(m.any()):
            break
        xt[m] = xt[m] + (MIN_GAP + 0.002 - dd[m])[:, None] * nn[m]
    return xt.numpy().copy()


def stitch_distances(mesh, x_unsewn) -> list[dict]:
    """How well each stitch's two edges face each other in a placement.

    Args:
        mesh: GarmentMesh. x_unsewn: (Nu, 3) [m] positions of the unsewn vertices.

    Returns:
        one dict per stitch side pair (in ``mesh.edge_verts`` pairing order): ``a``, ``b``
        ((panel, edge) keys), ``pair`` [m] the mean distance between the vertices sewn together,
        ``other`` [m] the mean distance from the edges' vertices to the nearest vertex of any
        other panel (neither a's nor b's).
    """
    from scipy.spatial import cKDTree

    x = np.asarray(x_unsewn, np.float64)
    sp = np.asarray(mesh.seam_pairs)
    part = np.asarray(mesh.uv_panel)
    # group seam pairs by the (panel, edge) keys of their two sides
    key_of = {}
    for key, idx in mesh.edge_verts.items():
        for i in np.asarray(idx):
            key_of.setdefault(int(i), []).append(key)
    groups: dict = {}
    for i, j in sp:
        ka = [k for k in key_of.get(int(i), [])]
        kb = [k for k in key_of.get(int(j), [])]
        # the edge pair: the one combination that holds most pairs (corners sit on two edges)
        for a in ka:
            for b in kb:
                groups.setdefault((a, b), []).append((int(i), int(j)))
    out = []
    for (a, b), pairs in groups.items():
        if len(pairs) < 2:
            continue
        pairs = np.array(pairs)
        pa, pb = mesh.panel_names.index(a[0]), mesh.panel_names.index(b[0])
        others = (part != pa) & (part != pb)
        d_pair = float(np.linalg.norm(x[pairs[:, 0]] - x[pairs[:, 1]], axis=1).mean())
        if others.any():
            tree = cKDTree(x[others])
            q = np.unique(pairs.ravel())
            d_other = float(tree.query(x[q])[0].mean())
        else:
            d_other = float("inf")
        out.append(dict(a=a, b=b, pair=d_pair, other=d_other))
    # keep only true stitch edge pairs (drop corner-induced combinations holding few pairs)
    best: dict = {}
    for r in out:
        n = len(groups[(r["a"], r["b"])])
        if n >= 0.5 * min(len(mesh.edge_verts[r["a"]]), len(mesh.edge_verts[r["b"]])):
            best[(r["a"], r["b"])] = r
    return list(best.values())
