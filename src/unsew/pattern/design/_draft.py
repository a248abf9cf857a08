"""Drafting a :class:`~unsew.pattern.design.Design` for a body: tops, dresses (one piece, or a
bodice and a skirt sewn at the waist), skirts of N panels, trousers, jumpsuits (a bodice and
trousers sewn at the waist), all placed around the body as the library's bases
(:mod:`unsew.pattern.base._frame`)."""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from unsew.errors import InputError
from unsew.pattern.base import dress as _dress
from unsew.pattern.base import pants as _pants
from unsew.pattern.base import skirt as _skirt
from unsew.pattern.base._band import BAND_HEIGHT
from unsew.pattern.base._build import quad, stitch
from unsew.pattern.base._frame import CLEARANCE, DEPTH_PER_GIRTH, BodyFrame, body_frame
from unsew.pattern.base.tshirt import BUST_EASE, TopSpec, sleeveless_frame
from unsew.pattern.base.tshirt import HIP_EASE as TEE_HIP_EASE
from unsew.pattern.design._choices import LEGGED, LENGTHS, Design, design_name
from unsew.pattern.design._darts import BODICE_DART, band_between, dart_edge, symmetric_darts
from unsew.pattern.design._trouser_cuffs import cuff_legs
from unsew.pattern.design._trouser_darts import dart_trousers
from unsew.pattern.design._skirt import SkirtCut, skirt_panels
from unsew.pattern.design._collar import collar_set
from unsew.pattern.design._top import (
    CUFF_HEIGHT,
    NECK_DEPTHS,
    hem_cuts,
    sleeve_set,
    strapless_panels,
    top_panels,
    top_stitches,
)
from unsew.pattern.measurements import Measurements
from unsew.pattern.model import Pattern

__all__ = ["draft", "length_to"]

#: A torso's width over its depth at the hips [-] (the ellipse of :data:`DEPTH_PER_GIRTH`).
TORSO_ASPECT = 0.7
#: A t-shirt's hem below the hips [m] (the library's).
TEE_HEM_DROP = 0.02
#: A top's side seam under the armpit at least this long [m] (a crop top's hem).
MIN_TOP_SIDE = 0.05
#: A trouser hem at least this far below the crotch point [m].
MIN_INSEAM = 0.03
#: A trouser leg's cuff at least this high [m] (it is shortened to keep MIN_INSEAM).
MIN_CUFF = 0.02


def length_to(m: Measurements, where: str) -> float:
    """How far below the natural waist [m] a hem at ``where`` sits on a body of measurements ``m``:
    ``hip`` (the fullest hips), ``mini`` (half-way from the crotch to the knee), ``knee`` (the
    library skirts' knee, 0.75 of the leg length), ``midi`` (half-way from the knee to the ankle),
    ``ankle`` (the library trousers' hem)."""
    if where not in LENGTHS:
        raise InputError(f"unknown hem position {where!r}; choose one of {', '.join(LENGTHS)}")
    f = body_frame(m)
    knee = _skirt.LENGTH_PER_LEG * m.leg_length
    ankle = f.waist_y - _pants.PANTS_HEM_HEIGHT * m.height / 1.70
    return {
        "hip": f.waist_y - f.hip_y,
        "mini": 0.5 * (f.waist_y - f.crotch_y + knee),
        "knee": knee,
        "midi": 0.5 * (knee + ankle),
        "ankle": ankle,
    }[where]


def _pattern(panels: dict, stitches: list) -> Pattern:
    return Pattern("", panels, stitches, properties={"units_in_meter": 100, "curvature_coords": "relative"})


def _top(d: Design, m: Measurements, f: BodyFrame, spec: TopSpec, cuts=None, darts=None) -> tuple[dict, list]:
    """Front, back (cut to :func:`sleeveless_frame` without sleeves; their hem cut at ``cuts``
    [m] and labelled ``waist`` when given, or cut by the V notches ``darts``, :class:`Dart`s along
    the hem from its right end), sleeves and collar of a top, and their stitches."""
    necklines = (d.neckline_front, d.neckline_back)
    if d.strapless:
        front, back, k = strapless_panels(m, f, spec, d.top_drop)
    else:
        frame = sleeveless_frame(f) if d.sleeves == "none" else f
        front, back, k = top_panels(m, frame, spec, necklines, split_neck=d.collar != "none")
    pieces, dart_st = 1, []
    if cuts is not None:
        front, back = hem_cuts(front, cuts, "waist"), hem_cuts(back, cuts, "waist")
        pieces = len(cuts) + 1
    elif darts:
        front, st_f, _ = dart_edge(front, 0, darts, "hem")
        back, st_b, _ = dart_edge(back, 0, darts, "hem")
        pieces, dart_st = 1 + 3 * len(darts), st_f + st_b
    arms, arm_st = sleeve_set(m, f, front, back, k, hem_pieces=pieces, design=d)
    depths = (NECK_DEPTHS[d.neckline_back][1], NECK_DEPTHS[d.neckline_front][0])
    collar, collar_st = collar_set(d, m, f, front, back, depths)
    panels = {p.name: p for p in (front, back, *arms, *collar)}
    sides = top_stitches(front, back, k, pieces, shoulders=not d.strapless)
    return panels, sides + arm_st + dart_st + collar_st


def _bodice_darts(m: Measurements, f: BodyFrame, w_hem: float, hem_y: float) -> tuple[float, list]:
    """(the hem's cut half width [m], the hem's darts) of a front or back whose sewn hem is
    ``2 w_hem`` [m] wide at height ``hem_y`` [m]: two darts take :data:`BODICE_DART`'s share of
    the bust's half width beyond the hem's, the rest left to the side seams."""
    share, at, depth = BODICE_DART
    dw = share * max((m.bust + BUST_EASE) / 4 - w_hem, 0.0)
    darts = symmetric_darts(w_hem + dw, dw, depth * max(f.armpit_y - hem_y, 0.0), at)
    return (w_hem + dw if darts else w_hem), darts


def _tshirt(d: Design, m: Measurements) -> Pattern:
    f = body_frame(m)
    hem_y = f.hip_y - TEE_HEM_DROP if d.length is None else f.waist_y - d.length
    if f.armpit_y - hem_y < MIN_TOP_SIDE:
        where = "above" if hem_y > f.waist_y else "below"
        raise InputError(
            f"a top's hem {abs(100 * (f.waist_y - hem_y)):.0f} cm {where} the waist leaves "
            f"{100 * (f.armpit_y - hem_y):.0f} cm under the armpit on this body; at least "
            f"{100 * MIN_TOP_SIDE:.0f} cm are needed"
        )
    w_hem = (
        max((m.hip + TEE_HIP_EASE) / 4, (m.bust + BUST_EASE) / 4) if d.hem_girth is None else d.hem_girth / 4
    )
    darts = None
    if d.darts:
        w_hem, darts = _bodice_darts(m, f, w_hem, hem_y)
    spec = TopSpec(lower=((w_hem, 0.0),), lower_curves=(None,), hem_y=hem_y)
    return _pattern(*_top(d, m, f, spec, darts=darts))


def _one_piece_dress(d: Design, m: Measurements) -> Pattern:
    """A dress cut in one piece from neck to hem, waisted (``fitted``) or straight: the library's
    dresses at their own length and flare."""
    f0 = body_frame(m)
    f = sleeveless_frame(f0) if d.sleeves == "none" else f0
    own = _dress.HEM_HEIGHT if d.fitted else _dress.STRAIGHT_HEM_HEIGHT
    hem_y = own * m.height / 1.70 if d.length is None else f.waist_y - d.length
    flare = (
        d.hem_flare if d.hem_flare is not None else (_dress.HEM_FLARE if d.fitted else _dress.STRAIGHT_FLARE)
    )
    hip_w = (m.hip + _dress.HIP_EASE) / 4
    if d.hem_girth is not None:
        flare = d.hem_girth / 4 - hip_w
    hip = np.array([hip_w, f.hip_y - hem_y])
    hem = np.array([hip_w + flare, 0.0])
    if not d.fitted:
        spec = TopSpec(lower=(tuple(hem), tuple(hip)), lower_curves=(None, None), hem_y=hem_y)
        return _pattern(*_top(d, m, f0, spec))
    top_y = f0.armpit_y - d.top_drop if d.strapless else f.armpit_y  # the side seam's top
    under = np.array([(m.bust + BUST_EASE) / 4, top_y - hem_y])
    mid = np.array([(m.waist + _dress.WAIST_EASE) / 4, f.waist_y - hem_y])
    # quadratic through the waist: its middle (a + 2c + b)/4 at the waist width
    curve = quad(hip, under, 2 * mid - (hip + under) / 2)
    spec = TopSpec(lower=(tuple(hem), tuple(hip)), lower_curves=(None, curve), hem_y=hem_y)
    return _pattern(*_top(d, m, f0, spec))


def _theta(d: Design, top: float, hip: float, hip_depth: float) -> float:
    """A cone skirt's unrolled angle [rad]: the circle's fraction of a turn, or what the hips
    need over ``hip_depth`` [m] plus the A-line's flare."""
    if d.skirt == "circle":
        return 2 * np.pi * d.circle_fraction
    return (hip - top) / hip_depth + d.aline_flare


def _skirt_cut(d: Design, m: Measurements, f: BodyFrame, top: float, hip: float, top_drop: float):
    """The :class:`SkirtCut` of ``d`` whose top (girth ``top`` [m]) sits ``top_drop`` [m] below
    the waist, over hips of girth ``hip`` [m] (ease included)."""
    length = (d.length if d.length is not None else length_to(m, "knee")) - top_drop
    hip_depth = f.waist_y - f.hip_y - top_drop
    if length <= hip_depth + 0.02 and d.skirt == "pencil":
        raise InputError(f"a pencil skirt reaches below the hips; length {d.length} m is too short")
    ax = m.hip * DEPTH_PER_GIRTH / 2 / TORSO_ASPECT + CLEARANCE
    return SkirtCut(
        style=d.skirt,
        panels=d.panels,
        top=top,
        hip=hip,
        top_y=f.waist_y - top_drop,
        hip_depth=hip_depth,
        length=length,
        theta=_theta(d, top, hip, hip_depth),
        axes=(ax, f.hip_z),
        band=d.waistband,
        hem=d.hem_girth if d.skirt == "pencil" else None,
        darts=d.darts,
    )


def _skirt_garment(d: Design, m: Measurements) -> Pattern:
    if d.skirt == "darted":
        if d.darts:
            raise InputError("the darted skirt has its own darts; leave darts unset")
        if d.panels != 2 or not d.waistband:
            raise InputError("a darted skirt has 2 panels under a waistband; set panels=2, waistband=True")
        if d.length is not None:
            raise InputError("a darted skirt is knee length; leave its length unset")
        return _skirt.make_skirt_darts(m)
    top_drop = BAND_HEIGHT if d.waistband else 0.0
    f, _, top, hip, _ = _skirt._girths(m, top_drop)
    panels, st, _ = skirt_panels(_skirt_cut(d, m, f, top, hip, top_drop), depth_z=f.hip_z)
    return _pattern(panels, st)


def _seamed_dress(d: Design, m: Measurements) -> Pattern:
    """A bodice from the natural waist to the neck and a skirt of ``d.panels`` gores, the bodice's
    waist cut in one piece per gore and sewn to the gores' tops; under a waistband
    (``d.waistband``) the bodice ends BAND_HEIGHT above the waist, the band between them, and the
    bodice may take waist darts (``d.darts``)."""
    if d.skirt == "darted":
        raise InputError("a dress's skirt is aline, pencil or circle; darted skirts stand alone")
    if d.darts and not d.waistband:
        raise InputError("a waist-seamed dress takes bodice darts under a waistband; set waistband=True")
    f = body_frame(m)
    waist_w = (m.waist + _dress.WAIST_EASE) / 4
    half = d.panels // 2
    length = d.length if d.length is not None else f.waist_y - _dress.HEM_HEIGHT * m.height / 1.70
    cut = _skirt_cut(
        replace(d, length=length, waistband=False, darts=False),
        m,
        f,
        4 * waist_w,
        m.hip + _dress.HIP_EASE,
        0.0,
    )
    gores, gore_st, tops = skirt_panels(cut, prefix="skirt_", depth_z=f.hip_z)
    if d.waistband:
        return _banded_dress(d, m, f, waist_w, (gores, gore_st, tops))
    spec = TopSpec(lower=((waist_w, 0.0),), lower_curves=(None,), hem_y=f.waist_y)
    cuts = [-waist_w + 2 * waist_w * j / half for j in range(1, half)]
    panels, st = _top(d, m, f, spec, cuts)
    panels.update(gores)
    st += gore_st
    for side, gs in (("front", tops[:half]), ("back", tops[half:])):
        for j, (g, e) in enumerate(gs):
            st.append(stitch(side, j, g, e, f"{side}_waist" + (f"_{j}" if half > 1 else "")))
    return _pattern(panels, st)


def _banded_dress(d: Design, m: Measurements, f: BodyFrame, waist_w: float, skirt) -> Pattern:
    """A waist-seamed dress's bodice ending BAND_HEIGHT above the waist, over a front and a back
    band sewn to it and to the gores' tops (``skirt``: :func:`skirt_panels`' gores, stitches
    and tops), the bodice's hem darted when ``d.darts``."""
    gores, gore_st, tops = skirt
    half = d.panels // 2
    hem_y = f.waist_y + BAND_HEIGHT
    w_hem, darts = _bodice_darts(m, f, waist_w, hem_y) if d.darts else (waist_w, [])
    spec = TopSpec(lower=((w_hem, 0.0),), lower_curves=(None,), hem_y=hem_y)
    panels, st = _top(d, m, f, spec, darts=darts)
    panels.update(gores)
    st += gore_st
    below = {side: gs for side, gs in (("front", tops[:half]), ("back", tops[half:]))}
    return _pattern(panels, st + _band_under_bodice(panels, below, f))


def _band_under_bodice(panels: dict, below: dict, f: BodyFrame) -> list:
    """A front and a back band from the waist up BAND_HEIGHT (added to ``panels``) sewn to the
    bodice's hem pieces (``panels``' ``front`` and ``back``) and to the edges ``below``
    ({"front": [(panel, edge)], "back": [...]}, in the band's +x order, :func:`band_between`);
    their stitches."""
    from unsew.pattern.curves import edge_length

    above, under = {}, {}
    for side, edges in below.items():
        under[side] = [(pn, e, edge_length(panels[pn], e)) for pn, e in edges]
        hem = [
            j for j, e in enumerate(panels[side].edges) if e.label.startswith("hem") and "dart" not in e.label
        ]
        above[side] = [(side, j, edge_length(panels[side], j)) for j in hem]
        # the band is as wide as the edges below; the bodice's sewn hem meets it to rounding
        scale = sum(p[2] for p in under[side]) / sum(p[2] for p in above[side])
        above[side] = [(pn, e, ln * scale) for pn, e, ln in above[side]]
    bands, band_st = band_between(under, above, bottom_y=f.waist_y, height=BAND_HEIGHT, depth_z=f.hip_z)
    panels.update(bands)
    return band_st


def _dress_garment(d: Design, m: Measurements) -> Pattern:
    if d.darts and not d.waist_seam:
        raise InputError("a one-piece dress takes no waist darts; darts need waist_seam=True")
    return _seamed_dress(d, m) if d.waist_seam else _one_piece_dress(d, m)


def _legs_cut(d: Design, m: Measurements) -> tuple[float, float, float]:
    """Hem height [m], a front leg panel's hem half width [m] and the cuffs' height [m] of ``d``'s
    trousers: the library's pants or shorts, a knee length half-way between them, or
    ``d.length``; with ``d.leg_cuffs`` the legs end a cuff's height higher (less where the inseam
    would end above :data:`MIN_INSEAM`), the cuffs' lower edge at the hem, as wide as it."""
    f = body_frame(m)
    y_full = _pants.PANTS_HEM_HEIGHT * m.height / 1.70
    half_full = _pants.PANTS_HEM_GIRTH / 4 - 0.01
    y_short = f.crotch_y - _pants.CROTCH_DROP - _pants.SHORTS_INSEAM
    half_short = (m.thigh + _pants.SHORTS_HEM_EASE) / 4 - 0.01
    leg = d.leg or LEGGED[d.garment]
    if d.length is not None:
        hem_y = f.waist_y - d.length
    else:
        hem_y = {"full": y_full, "shorts": y_short, "knee": f.waist_y - length_to(m, "knee")}[leg]
    room = f.crotch_y - _pants.CROTCH_DROP - MIN_INSEAM - hem_y
    if room < 0.0:
        raise InputError(f"trousers' hem {f.waist_y - hem_y:.3f} m below the waist is above the crotch")
    cuff = min(CUFF_HEIGHT, room) if d.leg_cuffs else 0.0
    if d.leg_cuffs and cuff < MIN_CUFF:
        raise InputError(f"trousers' hem {f.waist_y - hem_y:.3f} m below the waist leaves no room for a cuff")
    t = (hem_y - y_short) / (y_full - y_short)  # 0 at the shorts' hem, 1 at the ankle
    half = half_short if t == 0.0 else (half_full if t == 1.0 else half_short + t * (half_full - half_short))
    if d.hem_girth is not None:  # a leg's hem: front and back, each two half widths, the back's
        # inseam end further out by the difference of the crotch extensions (pants._leg)
        half = (d.hem_girth - (_pants.BACK_CROTCH_EXT - _pants.FRONT_CROTCH_EXT) * m.hip) / 4
    return hem_y + cuff, half + (d.hem_flare or 0.0), cuff


def _trousers(d: Design, m: Measurements) -> Pattern:
    hem_y, half, cuff = _legs_cut(d, m)
    p = _pants._legs(m, hem_y, half, "", band=d.waistband)
    p = dart_trousers(p, m, band=d.waistband) if d.darts else p
    return cuff_legs(p, cuff) if d.leg_cuffs else p


def _jumpsuit(d: Design, m: Measurements) -> Pattern:
    """A bodice and trousers sewn at the natural waist: the bodice's waist cut at the centre,
    each half sewn to a leg panel's waist (as the library's trouser waistbands are); under a
    waistband (``d.waistband``) the bodice ends BAND_HEIGHT above the waist, the band between it
    and the legs, as a banded dress's."""
    if d.darts:
        raise InputError("the design space's jumpsuits take no darts")
    f = body_frame(m)
    hem_y, half, cuff = _legs_cut(d, m)
    legs = _pants._legs(m, hem_y, half, "", band=False)
    legs = cuff_legs(legs, cuff) if d.leg_cuffs else legs
    waist_w = (m.waist + _pants.WAIST_EASE) / 4  # a leg panel's waist edge
    if d.waistband:  # the bodice ends a band's height above the waist, the band between
        spec = TopSpec(lower=((waist_w, 0.0),), lower_curves=(None,), hem_y=f.waist_y + BAND_HEIGHT)
        panels, st = _top(d, m, f, spec)
        panels.update(legs.panels)
        below = {
            "front": [("right_front", 2), ("left_front", 3)],
            "back": [("left_back", 2), ("right_back", 3)],
        }
        return _pattern(panels, st + legs.stitches + _band_under_bodice(panels, below, f))
    spec = TopSpec(lower=((waist_w, 0.0),), lower_curves=(None,), hem_y=f.waist_y)
    panels, st = _top(d, m, f, spec, [0.0])
    panels.update(legs.panels)
    st += legs.stitches + [
        stitch("front", 0, "right_front", 2, "right_front_waist"),
        stitch("front", 1, "left_front", 3, "left_front_waist"),
        stitch("back", 0, "left_back", 2, "left_back_waist"),
        stitch("back", 1, "right_back", 3, "right_back_waist"),
    ]
    return _pattern(panels, st)


#: Garments that hang from their open top (a skirt's or trousers' waist, or their band's top).
HANGING = ("skirt", "pants", "shorts")
#: The label GarmentCode's programs give the edge a lower garment hangs from.
HANGING_LABEL = "lower_interface"


def _label_hanging_top(p: Pattern) -> None:
    """Label ``p``'s open top edges (``waist*``, a band's ``top``) :data:`HANGING_LABEL`: dressed,
    they are held where the pattern places them, as GarmentCode's simulation holds a lower
    garment's top (:data:`unsew.dress.ATTACH_LABELS`, docs/decisions/045)."""
    from unsew.grading.curves import stitched_edges

    sewn = stitched_edges(p)
    for name, pan in p.panels.items():
        for i, e in enumerate(pan.edges):
            if (name, i) not in sewn and (e.label.startswith("waist") or e.label == "top"):
                e.label = HANGING_LABEL


#: Garments whose bodice is joined at the waist to a lower part (a skirt, a band, trouser legs).
JOINED = ("dress", "jumpsuit")
#: The panels of a bodice.
BODICE = ("front", "back")


def _label_joined_top(p: Pattern) -> None:
    """Label the lower part's top edges sewn to the bodice (a skirt's or legs' ``waist``, a band's
    ``top*``) :data:`HANGING_LABEL`, as GarmentCode's programs label a dress's or jumpsuit's
    waist seam: its simulation holds them, so the exported pattern drapes there as the designs it
    reads do. :func:`unsew.dress.dress` holds open labelled edges only: unsew's drapes are
    unchanged."""
    for s in p.stitches:
        for me, other in ((s.a, s.b), (s.b, s.a)):
            e = p.panels[me.panel].edges[me.edge]
            if other.panel in BODICE and me.panel not in BODICE and e.label.startswith(("waist", "top")):
                e.label = HANGING_LABEL


_DRAFTERS = {
    "tshirt": _tshirt,
    "dress": _dress_garment,
    "skirt": _skirt_garment,
    "pants": _trousers,
    "shorts": _trousers,
    "jumpsuit": _jumpsuit,
}


def draft(design: Design, measurements: Measurements | None = None) -> Pattern:
    """The :class:`~unsew.pattern.model.Pattern` of ``design`` sized to ``measurements`` (default:
    the default body) and placed around that body (world frame, metres): closed
    counter-clockwise panels, stitches of equal-length edges, named by
    :func:`~unsew.pattern.design.design_name`, the design recorded under ``pattern.unsew["design"]``.

    A ``length`` given as a place on the body (``"knee"``) is measured on this body
    (:func:`length_to`). Raises :class:`~unsew.errors.InputError` for a combination that cannot
    be cut (a darted skirt of more than two panels, trousers whose hem is above the crotch)."""
    if not isinstance(design, Design):
        raise InputError(f"draft needs a Design, not {type(design).__name__}")
    m = measurements or Measurements()
    if design.ease:
        e = design.ease
        m = replace(m, bust=m.bust + e, waist=m.waist + e, hip=m.hip + e)
    d = replace(design, length=length_to(m, design.length)) if isinstance(design.length, str) else design
    p = _DRAFTERS[design.garment](d, m)
    if design.garment in HANGING:
        _label_hanging_top(p)
    elif design.garment in JOINED:
        _label_joined_top(p)
    p.name = design_name(design)
    p.unsew["design"] = design.as_dict()
    return p
