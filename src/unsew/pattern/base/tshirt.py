"""Base t-shirt: front, back, two short set-in sleeves (paper Fig. 2a); variants with long
sleeves tapering to the wrist (``tshirt_long``) and without sleeves (``tshirt_sleeveless``).

Front and back are mirror-symmetric about their vertical centre lines (x = 0 in the panel
frame); the two sleeves are mirror images. Every panel is counter-clockwise seen from outside
the garment, and stitches follow :mod:`unsew.pattern.model`'s convention (a.start meets b.end).

Panel-frame layout of the front and back (x across, y up, y = 0 at the hem)::

    edge 0 hem, 1 right side seam, 2 right armhole, 3 right shoulder, 4 neckline,
    5 left shoulder, 6 left armhole, 7 left side seam
    ("right"/"left" are the panel's +x/-x sides; the front's +x is the body's left).

Sleeve (one panel per arm, its underarm seam sewn to itself)::

    edge 0 hem, 1 +x underarm seam, 2 +x cap half, 3 -x cap half, 4 -x underarm seam
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from unsew.pattern.measurements import Measurements
from unsew.pattern.base._build import cubic, place, rot_y180, solve_length, stitch, symmetric_panel
from unsew.pattern.base._frame import BodyFrame, body_frame
from unsew.pattern.curves import edge_length
from unsew.pattern.model import Curvature, Panel, Pattern, Stitch

__all__ = [
    "make_tshirt",
    "make_tshirt_long",
    "make_tshirt_sleeveless",
    "TopSpec",
    "top_panels",
    "sleeve_panels",
    "sleeves_for",
    "sleeveless_frame",
    "BUST_EASE",
    "SLEEVES",
    "NECKLINES",
]

#: Ease over the bust girth [m] (a regular-fit t-shirt: 8-15 cm).
BUST_EASE = 0.12
#: Ease over the hip girth at a t-shirt hem [m].
HIP_EASE = 0.08
#: Ease over the upper-arm girth [m].
ARM_EASE = 0.08
#: Lowest sleeve cap height [m] (cap top over the underarm points): a flatter cap than the
#: armhole needs narrows the sleeve instead (:func:`sleeve_panels`).
CAP_MIN = 0.01
#: Front and back neckline depths below the neck points [m].
FRONT_NECK_DEPTH = 0.08
BACK_NECK_DEPTH = 0.02
#: Neckline shapes of a front or back: a curve between the neck points, or two straight edges
#: meeting at a point on the centre line (a V, whose point is a control point).
NECKLINES = ("round", "v")
#: A V neckline's point below the neck points [m], front and back.
FRONT_V_DEPTH = 0.15
BACK_V_DEPTH = 0.08
#: Short sleeve: cap top to hem [m].
SHORT_SLEEVE_LENGTH = 0.22
#: Long sleeve: cap top to hem beyond the arm length (shoulder joint to wrist joint) [m]; the
#: cap top sits on the shoulder tip, a little outside the joint.
LONG_SLEEVE_EXTRA = 0.02
#: Wrist girth per upper-arm girth (adult proportions: about 16 of 27 cm) [-], and the ease over
#: it at a long sleeve's hem [m] (the hand must pass).
WRIST_PER_UPPER_ARM = 0.6
WRIST_EASE = 0.10
#: Sleeveless tops: the shoulder seam ends this much nearer the neck than a sleeved top's [m],
#: and the armhole's bottom sits this much higher [m] (a cut-in armhole that does not gape).
SLEEVELESS_SHOULDER_IN = 0.04
SLEEVELESS_ARMHOLE_RAISE = 0.015
#: Sleeve variants of a top.
SLEEVES = ("short", "long", "none")


@dataclass(frozen=True)
class TopSpec:
    """The right half of a top's front/back below the underarm (panel frame [m], y = 0 at hem).

    lower: points from the hem corner up to (excluding) the underarm point, (k, 2) [m].
    lower_curves: curvatures of the k segments between them and the underarm point.
    """

    lower: tuple
    lower_curves: tuple
    hem_y: float  #: world height of the hem [m]


def _neckline(a, b, depth: float) -> Curvature:
    """Self-symmetric cubic neckline from the right neck point ``a`` to the left one ``b``,
    dipping ``depth`` [m] at the centre."""
    a, b = np.asarray(a), np.asarray(b)
    # A cubic with both control points at height y - d*4/3 dips d at its middle.
    y = a[1] - depth * 4.0 / 3.0
    return cubic(a, b, (a[0] * 0.9, y), (b[0] * 0.9, y))


def _armhole(under, tip) -> Curvature:
    """Armhole from the underarm point up to the shoulder tip, scooped towards the centre."""
    under, tip = np.asarray(under), np.asarray(tip)
    dx, dy = under[0] - tip[0], tip[1] - under[1]
    return cubic(
        under, tip, (under[0] - 0.9 * dx, under[1] + 0.02 * dy / 0.2), (tip[0] - 0.012, under[1] + 0.55 * dy)
    )


def top_panels(
    m: Measurements, f: BodyFrame, spec: TopSpec, *, necklines: tuple[str, str] = ("round", "round")
) -> tuple[Panel, Panel, int]:
    """Front and back panels of a top [m]; returns (front, back, number of lower segments k).
    necklines: the front's and the back's shape, each one of :data:`NECKLINES`.

    Edge numbering (k lower segments): 0 hem; 1..k right side below the underarm; k+1 right
    armhole; k+2 right shoulder; k+3 neckline (a V: k+3 its right half, k+4 its left half);
    then the mirrored left edges.
    """
    bad = [n for n in necklines if n not in NECKLINES]
    if bad or len(necklines) != 2:
        raise ValueError(f"necklines must be two of {NECKLINES} (front, back), not {necklines!r}")
    w = (m.bust + BUST_EASE) / 4
    neck_w = m.neck / (2 * np.pi) + 0.015
    under = np.array([w, f.armpit_y - spec.hem_y])
    tip = np.array([f.shoulder_x + 0.01, f.shoulder_y - spec.hem_y])
    neck = np.array([neck_w, f.neck_y - spec.hem_y])
    k = len(spec.lower)
    labels = ["right_side"] * k + ["right_armhole", "right_shoulder"]
    panels = []
    for name, depth, v_depth, shape in (
        ("front", FRONT_NECK_DEPTH, FRONT_V_DEPTH, necklines[0]),
        ("back", BACK_NECK_DEPTH, BACK_V_DEPTH, necklines[1]),
    ):
        half = [np.asarray(p) for p in spec.lower] + [under, tip, neck]
        curves = list(spec.lower_curves) + [_armhole(under, tip), None]
        if shape == "v":  # the half runs on to the V's point on the centre line: an apex, no top edge
            p, _ = symmetric_panel(
                name,
                half + [np.array([0.0, neck[1] - v_depth])],
                curves + [None],
                half_labels=labels + ["right_neckline"],
                bottom_label="hem",
            )
        else:
            neck_l = neck * np.array([-1.0, 1.0])
            p, _ = symmetric_panel(
                name,
                half,
                curves,
                top=_neckline(neck, neck_l, depth),
                half_labels=labels,
                bottom_label="hem",
                top_label="neckline",
            )
        panels.append(p)
    front, back = panels
    place(front, np.eye(3), (0.0, spec.hem_y, f.chest_z))
    place(back, rot_y180(), (0.0, spec.hem_y, -f.chest_z))
    return front, back, k


def _sleeve(name: str, ws: float, cap_h: float, under_len: float, hem_w: float | None = None) -> Panel:
    hem_w = ws - 0.01 if hem_w is None else hem_w
    half = [(hem_w, -under_len), (ws, 0.0), (0.0, cap_h)]
    a, b = np.array(half[1]), np.array(half[2])
    cap = cubic(a, b, (0.55 * ws, 0.15 * cap_h), (0.3 * ws, cap_h))
    p, _ = symmetric_panel(
        name, half, [None, cap], half_labels=["right_underarm", "right_cap"], bottom_label="hem"
    )
    return p


def sleeve_panels(
    m: Measurements,
    f: BodyFrame,
    armhole_length: float,
    *,
    length: float = SHORT_SLEEVE_LENGTH,
    hem_half: float | None = None,
):
    """Left and right sleeves whose cap halves are ``armhole_length`` [m] long each, ``length``
    [m] from cap top to hem, the hem ``2 * hem_half`` [m] across (None: 2 cm less than the
    sleeve's width at the underarm).

    The cap height is solved (bisection) so both cap halves match the armholes exactly.
    Returns (left_sleeve, right_sleeve).
    """
    ws = (m.upper_arm + ARM_EASE) / 2
    if edge_length(_sleeve("s", ws, CAP_MIN, 0.1), 2) > armhole_length:
        # even the flattest cap is longer than the armhole (an arm thick for its armhole): the
        # sleeve narrowed until it is not, so that the cap still sews into the armhole
        ws = solve_length(lambda w: _sleeve("s", w, CAP_MIN, 0.1), 2, armhole_length, 0.01, ws)
    cap_h = solve_length(lambda h: _sleeve("s", ws, h, 0.1), 2, armhole_length, CAP_MIN, 0.4)
    under_len = max(length - cap_h, 0.04)
    left = _sleeve("left_sleeve", ws, cap_h, under_len, hem_half)
    right = _sleeve("right_sleeve", ws, cap_h, under_len, hem_half)
    a, c, s = f.arm_angle, np.cos(f.arm_angle), np.sin(f.arm_angle)
    # Laid over each arm, outer side up, cap top at the shoulder tip, hem towards the wrist.
    R_left = np.column_stack([(0.0, 0.0, -1.0), (-c, s, 0.0), (s, c, 0.0)])
    R_right = np.column_stack([(0.0, 0.0, 1.0), (c, s, 0.0), (-s, c, 0.0)])
    up = 0.04
    place(left, R_left, (f.shoulder_x + up * s, f.shoulder_y + up * c, 0.0), (0.0, cap_h))
    place(right, R_right, (-f.shoulder_x - up * s, f.shoulder_y + up * c, 0.0), (0.0, cap_h))
    del a
    return left, right


def side_and_shoulder_stitches(n: dict, k: int, first: int = 1, *, shoulders: bool = True) -> list[Stitch]:
    """The side seams (``k`` segments a side) and shoulder seams (none unless ``shoulders``: a
    strapless top) of a top's front and back, whose
    outlines have ``n["front"]`` and ``n["back"]`` edges and whose right half starts at edge
    ``first`` (after the hem's ``first`` pieces), each left half the mirror of its right half.
    Front +x is the body's left, back +x the body's right (the back is seen from behind)."""
    right = lambda i: i + first  # noqa: E731  right-half segment i
    left = lambda p, i: n[p] - 1 - i  # noqa: E731  its mirror image on panel p
    st = []
    for i in range(k):
        side = "" if k == 1 else f"_{i}"
        st.append(stitch("front", right(i), "back", left("back", i), f"left_side{side}"))
        st.append(stitch("back", right(i), "front", left("front", i), f"right_side{side}"))
    if not shoulders:
        return st
    st.append(stitch("front", right(k + 1), "back", left("back", k + 1), "left_shoulder"))
    st.append(stitch("back", right(k + 1), "front", left("front", k + 1), "right_shoulder"))
    return st


def top_stitches(
    k: int, *, sleeves: bool = True, necklines: tuple[str, str] = ("round", "round")
) -> list[Stitch]:
    """Stitches of a top built by :func:`top_panels` (+ :func:`sleeve_panels`), with the same
    ``necklines``.

    Front +x is the body's left, back +x the body's right (the back is seen from behind).
    """
    # vertices (and edges) of the front and the back: a V adds its point
    n = {"front": 2 * k + 6 + (necklines[0] == "v"), "back": 2 * k + 6 + (necklines[1] == "v")}
    right = lambda i: i + 1  # noqa: E731  right-half segment i
    left = lambda p, i: n[p] - 1 - i  # noqa: E731  its mirror image on panel p
    arm = k  # segment index of the armhole
    st = side_and_shoulder_stitches(n, k)
    if sleeves:
        # Sleeve edges: 1 +x underarm, 2 +x cap, 3 -x cap, 4 -x underarm. The left sleeve's +x
        # side faces the back, the right sleeve's +x side faces the front.
        st.append(stitch("front", right(arm), "left_sleeve", 3, "left_armhole_front"))
        st.append(stitch("back", left("back", arm), "left_sleeve", 2, "left_armhole_back"))
        st.append(stitch("front", left("front", arm), "right_sleeve", 2, "right_armhole_front"))
        st.append(stitch("back", right(arm), "right_sleeve", 3, "right_armhole_back"))
        st.append(stitch("left_sleeve", 1, "left_sleeve", 4, "left_underarm"))
        st.append(stitch("right_sleeve", 1, "right_sleeve", 4, "right_underarm"))
    return st


def sleeveless_frame(f: BodyFrame) -> BodyFrame:
    """The landmarks a sleeveless top is cut to: shoulder seam shorter, armhole higher."""
    return dataclasses.replace(
        f, shoulder_x=f.shoulder_x - SLEEVELESS_SHOULDER_IN, armpit_y=f.armpit_y + SLEEVELESS_ARMHOLE_RAISE
    )


def sleeves_for(m: Measurements, f: BodyFrame, armhole_length: float, sleeves: str) -> tuple[Panel, ...]:
    """The sleeve panels of a top: () for ``"none"``, else (left, right) short or long sleeves."""
    if sleeves not in SLEEVES:
        raise ValueError(f"sleeves must be one of {SLEEVES}, not {sleeves!r}")
    if sleeves == "none":
        return ()
    if sleeves == "short":
        return sleeve_panels(m, f, armhole_length)
    wrist = (WRIST_PER_UPPER_ARM * m.upper_arm + WRIST_EASE) / 2
    return sleeve_panels(m, f, armhole_length, length=m.arm_length + LONG_SLEEVE_EXTRA, hem_half=wrist)


def top_pattern(
    family: str,
    m: Measurements,
    f: BodyFrame,
    spec: TopSpec,
    sleeves: str,
    *,
    necklines: tuple[str, str] = ("round", "round"),
) -> Pattern:
    """A top of ``family`` (``"tshirt"``, ``"dress"`` or ``"dress_straight"``): front and back of ``spec``
    (armholes cut in as :func:`sleeveless_frame` when ``sleeves`` is ``"none"``, necklines of
    :data:`NECKLINES` front and back), the sleeves sized to the armhole, and the stitches. Named ``family``,
    ``family_long`` or ``family_sleeveless``."""
    front, back, k = top_panels(m, sleeveless_frame(f) if sleeves == "none" else f, spec, necklines=necklines)
    arm = sleeves_for(m, f, edge_length(front, k + 1), sleeves)
    panels = {p.name: p for p in (front, back, *arm)}
    name = family + {"short": "", "long": "_long", "none": "_sleeveless"}[sleeves]
    st = top_stitches(k, sleeves=bool(arm), necklines=necklines)
    return Pattern(name, panels, st, properties={"units_in_meter": 100, "curvature_coords": "relative"})


def make_tshirt(
    m: Measurements | None = None, *, sleeves: str = "short", necklines: tuple[str, str] = ("round", "round")
) -> Pattern:
    """A t-shirt sized to ``m`` (default: the default body), placed around it; ``sleeves``:
    ``"short"`` (pattern ``tshirt``), ``"long"`` (``tshirt_long``) or ``"none"`` (a tank top,
    ``tshirt_sleeveless``, cut to :func:`sleeveless_frame`); ``necklines``: front and back, of
    :data:`NECKLINES`."""
    m = m or Measurements()
    f = body_frame(m)
    hem_y = f.hip_y - 0.02
    w_hem = max((m.hip + HIP_EASE) / 4, (m.bust + BUST_EASE) / 4)
    spec = TopSpec(lower=((w_hem, 0.0),), lower_curves=(None,), hem_y=hem_y)
    return top_pattern("tshirt", m, f, spec, sleeves, necklines=necklines)


def make_tshirt_long(m: Measurements | None = None, **kw) -> Pattern:
    """The t-shirt with long sleeves tapering to the wrist (``kw``: :func:`make_tshirt`'s necklines)."""
    return make_tshirt(m, sleeves="long", **kw)


def make_tshirt_sleeveless(m: Measurements | None = None, **kw) -> Pattern:
    """The t-shirt without sleeves (a tank top), its armholes cut in."""
    return make_tshirt(m, sleeves="none", **kw)
