"""The fit's candidate designs when meta.json names no garment type: a handful of points of the
design space (:mod:`unsew.pattern.design`) consistent with the design read off the target
(:func:`unsew.grading.design_reading.read_design`).

The reading's choices are fixed: the type, the sleeves, the necklines, a hood or a standing
(turtle) collar on a top (every candidate carries it), the hem's length (metres,
from the hem's depth as a share of the leg) and the skirt's flare, turned into the cone's angle
whose drape has that flare (an A-line's ``aline_flare``, a circle's ``circle_fraction``), and
the waist darts the reading decided (a two-panel pencil skirt's; a dress cut to the body at the
chest is drafted first as a bodice with waist darts over a waistband and a skirt). The
alternatives are the choices the reading cannot see (a waistband, the number of gores, a dress in
one piece or a bodice and a skirt, sleeves in two pieces, cuffs), the neighbouring sleeve classes
where the sleeve's share is uncertain or near a class's edge (:data:`SLEEVE_MARGIN`) and the
neighbouring skirt style where the flare lies near a class's edge (:data:`FLARE_MARGIN`). At most
:data:`MAX_CANDIDATES`, the design as read first; each is dressed and compared as the library's
bases are (:func:`unsew.fit.start.choose_base`).
"""

from __future__ import annotations

import numpy as np

from unsew.errors import InputError
from unsew.grading.design_reading import ANKLE_HEIGHT, ARMHOLE_SHARE, FLARE_EDGES, SHORT_SLEEVE_SHARE
from unsew.pattern.base import skirt as _skirt
from unsew.pattern.base._band import BAND_HEIGHT
from unsew.pattern.design import GARMENTS, STRAPLESS_DROP, TOP_DROP_RANGE, Design, design_name, draft
from unsew.pattern.measurements import Measurements

__all__ = [
    "design_candidates",
    "drafted_candidates",
    "read_measures",
    "MAX_CANDIDATES",
    "FLARE_MARGIN",
    "SLEEVE_MARGIN",
]

#: The most candidates one reading gives (each is one drape on the base choice's coarse mesh).
MAX_CANDIDATES = 6
#: A flare within this ratio of a class edge adds the neighbouring skirt style.
FLARE_MARGIN = 1.06
#: A sleeve share read where the arm line passes through the opening, within this share of the
#: arm of a class edge, adds the neighbouring sleeve class (docs/decisions/052).
SLEEVE_MARGIN = 0.1
#: The reading's necklines as a design's (no neck opening, or none read: round).
_NECK = {"round": "round", "v": "v", "square": "square"}
#: The reading's collars the design space drafts (a hood, a standing collar).
_COLLARS = ("hood", "turtle")
#: Trouser legs by the reading's length class.
_LEG = {"above knee": "shorts", "knee": "knee", "below knee": "full"}
#: A read hem girth is kept within these shares of the hips' girth (tops, dresses, skirts): a
#: loop that is not the hem (a torn or folded mesh) gives no design.
HEM_PER_HIP = (0.7, 1.6)


def _loop_length(v: np.ndarray, loop) -> float:
    """The length [m] of a closed contour (its ``indices`` into v (V, 3) [m])."""
    idx = np.r_[loop.indices, loop.indices[0]]
    return float(np.linalg.norm(np.diff(v[idx], axis=0), axis=1).sum())


def read_measures(verts, faces, skeleton, *, contours=None) -> dict:
    """Continuous measures of a draped garment its drafted designs take (the cloth barely
    stretches, so an opening's length is the pattern's hem length):

    - ``hem_girth`` [m], ``hem_y`` [m]: the lowest torso opening's length and median height (a
      top's, a dress's or a skirt's hem);
    - ``leg_girth`` [m]: the mean length of the openings round the legs (trousers' hems; not
      drafted: the fit's trousers keep their own, docs/decisions/024);
    - ``top_y`` [m]: the highest torso opening's median height, where the garment has two or more
      (a strapless top's edge; else the neck opening).

    verts: (V, 3) float64 [m], world frame; faces: (F, 3) int; skeleton: the wearer's
    :class:`~unsew.body.skeleton.Skeleton`; contours: the mesh's open contours when found. A key
    is absent where the garment has no such opening."""
    from unsew.grading.design_reading import _hem_loop
    from unsew.grading.garment_type import _openings_by_part
    from unsew.losses.contours import open_contours

    v = np.asarray(verts, dtype=np.float64)
    loops = open_contours(v, np.asarray(faces, dtype=np.int64)) if contours is None else contours
    if not loops:
        return {}
    centres = np.stack([np.asarray(c.centre, dtype=np.float64) for c in loops])
    leg, arm, _ = _openings_by_part(v, loops, centres, skeleton)
    out = {}
    torso = [c for c, off in zip(loops, leg | arm) if not off]
    if len(torso) > 1:  # a hem and a top: the highest's height (a strapless top's edge)
        out["top_y"] = max(float(np.median(v[np.asarray(c.indices), 1])) for c in torso)
    if leg.any():
        out["leg_girth"] = float(np.mean([_loop_length(v, c) for c, on in zip(loops, leg) if on]))
    else:
        hem = _hem_loop(v, loops, skeleton)
        if hem is not None:
            out["hem_girth"] = _loop_length(v, hem)
            out["hem_y"] = float(np.median(v[np.asarray(hem.indices), 1]))
    return out


def _hem_girth(measures: dict, m: Measurements) -> float | None:
    """The read hem's girth [m] within :data:`HEM_PER_HIP` of the hips', to 1 mm; None if not read."""
    g = measures.get("hem_girth")
    return None if g is None else round(float(np.clip(g, *(np.array(HEM_PER_HIP) * m.hip))), 3)


def _top_length(measures: dict, m: Measurements) -> float | None:
    """A top's hem below the natural waist [m] (at least 5 cm), from the read hem height."""
    y = measures.get("hem_y")
    if y is None:
        return None
    from unsew.pattern.base._frame import body_frame

    return round(float(np.clip(body_frame(m).waist_y - y, 0.05, 1.5)), 2)


def _hem_length(reading, m: Measurements) -> float | None:
    """The hem's (or the leg openings') depth below the natural waist [m], to 1 cm, on a body of
    measurements ``m``, from the reading's ``hem_share`` (its depth below the hip joints as a share
    of the hip joints' height over the floor, as :mod:`unsew.grading.design_reading` measures it);
    None when no hem was read."""
    share = reading.numbers.get("hem_share")
    if share is None:
        return None
    hip_joint = (1.0 + ANKLE_HEIGHT) * m.leg_length  # over the floor [m]
    return round(float(np.clip(m.waist_height - hip_joint * (1.0 - share), 0.1, 1.5)), 2)


def _cone_flare(theta: float, top: float, hip: float, length: float) -> float:
    """A cone skirt's flare as the reading measures it: its hem's length over the body's hip
    girth. theta: the unrolled angle [rad]; top: the cone's girth at its top [m]; hip: the body's
    hip girth [m]; length: the hem's depth below its top [m]."""
    return (top + theta * length) / hip


def _fitted_flare(reading, m: Measurements, length: float | None, style: str, *, band: bool = False):
    """The ``aline_flare`` [rad] (style "aline") or ``circle_fraction`` (style "circle") whose cone
    has the read flare, to 0.05; None when no flare was read."""
    flare = reading.numbers.get("flare")
    if flare is None:
        return None
    drop = BAND_HEIGHT if band else 0.0
    f, _, top, hip, _ = _skirt._girths(m, drop)
    h = f.waist_y - f.hip_y - drop  # the hips' depth, as the A-line is drafted
    L = (length if length is not None else 0.75 * m.leg_length) - drop
    if style == "aline":
        grid = np.arange(0.0, 2.0001, 0.05)
        thetas = (hip - top) / h + grid
    else:
        grid = np.arange(0.1, 1.0001, 0.05)
        thetas = 2 * np.pi * grid
    err = [abs(_cone_flare(t, top, m.hip, L) - flare) for t in thetas]
    return round(float(grid[int(np.argmin(err))]), 2)


def _skirt_style(reading) -> tuple[str, list[str]]:
    """(the design's skirt style for the reading's, the neighbouring styles when the flare lies
    within :data:`FLARE_MARGIN` of a class edge)."""
    style = {"pencil": "pencil", "a-line": "aline", "flared": "circle"}.get(reading.skirt, "aline")
    flare = reading.numbers.get("flare")
    near = []
    if flare is not None:
        for edge, (lo, hi) in zip(FLARE_EDGES, (("pencil", "aline"), ("aline", "circle"))):
            if edge / FLARE_MARGIN <= flare <= edge * FLARE_MARGIN:
                near.append(hi if style == lo else lo)
    return style, [s for s in near if s != style]


def _skirt_design(base: Design, style: str, reading, m: Measurements, length, hem=None) -> Design:
    """``base`` with skirt ``style``, its cone fitted to the read flare, a pencil's hem to the read
    girth ``hem`` [m] (None: the hips')."""
    d = base.replace(skirt=style, hem_girth=hem if style == "pencil" else None)
    if style in ("aline", "circle"):
        band = d.waistband and d.garment == "skirt"
        v = _fitted_flare(reading, m, length, style, band=band)
        if v is not None:
            d = d.replace(**({"aline_flare": v} if style == "aline" else {"circle_fraction": max(v, 0.1)}))
    return d


def _strapless_drop(measures: dict, m: Measurements) -> float:
    """A strapless top's edge below the armpits [m], to 1 cm, from the read top height."""
    y = measures.get("top_y")
    if y is None:
        return STRAPLESS_DROP
    from unsew.pattern.base._frame import body_frame

    return round(float(np.clip(body_frame(m).armpit_y - y, *TOP_DROP_RANGE)), 2)


def _top_fields(reading, m: Measurements, measures: dict) -> dict:
    """Sleeves, necklines and collar of a top as read (none read: short sleeves, round necklines,
    no collar); a hood or a turtle collar is sewn to round necklines (none are read under it); no
    cloth over the shoulders (no neckline read): a strapless top, its edge at the read height."""
    if reading.neck_front == reading.neck_back == "none" and reading.collar in (None, "none"):
        return dict(sleeves="none", strapless=True, top_drop=_strapless_drop(measures, m))
    collar = reading.collar if reading.collar in _COLLARS else "none"
    round_neck = collar != "none"
    return dict(
        sleeves=reading.sleeves or "short",
        neckline_front="round" if round_neck else _NECK.get(reading.neck_front, "round"),
        neckline_back="round" if round_neck else _NECK.get(reading.neck_back, "round"),
        collar=collar,
    )


def _top_alternatives(first: Design, reading) -> list[Design]:
    """The neighbouring sleeve classes, the one whose edge the read share lies nearer first
    (grading cannot grow or remove a sleeve): those of a share read off a sleeve end off the arm
    line (uncertain), and, of a share where the arm line passes through the opening, those whose
    edge lies within :data:`SLEEVE_MARGIN`; then two-piece sleeves and cuffs (which the reading
    cannot see) on a sleeved design; for a strapless top, the sleeveless one with a round neck."""
    if first.strapless:  # the reading may have missed straps: the sleeveless round neck
        return [first.replace(strapless=False, top_drop=STRAPLESS_DROP)]
    share = reading.numbers.get("sleeve_share", 0.0)
    sure = reading.numbers.get("sleeve_through", 0.0) > 0.5
    edges = {("none", "short"): ARMHOLE_SHARE, ("short", "long"): SHORT_SLEEVE_SHARE}
    near = sorted(
        (abs(share - e), pair)
        for pair, e in edges.items()
        if first.sleeves in pair and not (sure and abs(share - e) > SLEEVE_MARGIN)
    )
    out = [first.replace(sleeves=b if first.sleeves == a else a) for _, (a, b) in near]
    if first.sleeves != "none":
        out += [first.replace(sleeve_pieces=2), first.replace(cuffs=True)]
    return out


def _tshirt(reading, m: Measurements, meas: dict) -> tuple[Design, list[Design]]:
    """The read sleeves and necklines, its hem where and as wide as the target's; the same with
    waist darts at the hem last, where the reading decided them (a top cut to the body: waist
    darts alone did not bring a drafted top nearer a fitted true bodice, docs/decisions/030)."""
    first = Design(
        garment="tshirt",
        length=_top_length(meas, m),
        hem_girth=_hem_girth(meas, m),
        **_top_fields(reading, m, meas),
    )
    darted = [first.replace(darts=True)] if reading.darts else []
    return first, _top_alternatives(first, reading) + darted


def _dress(reading, m: Measurements, meas: dict) -> tuple[Design, list[Design]]:
    """One piece (fitted for an A-line, straight for a pencil skirt) or, for a flared skirt, a
    bodice and a circle skirt; the other ways of cutting it next; a one-piece dress's or a pencil
    skirt's hem as wide as the target's."""
    length = _hem_length(reading, m)
    hem = _hem_girth(meas, m)
    top = Design(garment="dress", length=length, **_top_fields(reading, m, meas))
    style, near = _skirt_style(reading)
    seamed = [
        _skirt_design(top.replace(waist_seam=True, panels=n), style, reading, m, length, hem) for n in (2, 4)
    ]
    fitted, straight = top.replace(fitted=True, hem_girth=hem), top.replace(fitted=False, hem_girth=hem)
    banded = seamed[0].replace(waistband=True, darts=bool(reading.darts))
    ways = {
        "pencil": [straight, fitted, seamed[0]],
        "aline": [fitted, seamed[0], straight, seamed[1]],
        "circle": [seamed[0], seamed[1], fitted],
    }[style]
    # a bodice that needs waist darts is cut at the waist, the darts ending in a band
    ways = [banded, *ways] if reading.darts else [*ways[:2], banded, *ways[2:]]
    ways += [_skirt_design(top.replace(waist_seam=True), s, reading, m, length, hem) for s in near]
    return ways[0], ways[1:3] + _top_alternatives(ways[0], reading)[:1] + ways[3:]


def _skirt_garment(reading, m: Measurements, meas: dict) -> tuple[Design, list[Design]]:
    """The read style and flare in two gores (a pencil's hem as wide as the target's; a pencil
    with waist darts where the reading decided them), then under a waistband, in more gores, and
    the neighbouring style."""
    length = _hem_length(reading, m)
    hem = _hem_girth(meas, m)
    style, near = _skirt_style(reading)
    base = Design(garment="skirt", length=length, darts=bool(reading.darts) and style == "pencil")
    first = _skirt_design(base, style, reading, m, length, hem)
    more = 6 if style == "circle" else 4
    plain = base.replace(darts=False)  # darts are cut in two panels only
    alts = [
        _skirt_design(base.replace(waistband=True), style, reading, m, length, hem),
        _skirt_design(plain.replace(panels=more), style, reading, m, length, hem),
    ]
    alts += [_skirt_design(plain, s, reading, m, length, hem) for s in near]
    alts.append(_skirt_design(plain.replace(waistband=True, panels=more), style, reading, m, length, hem))
    return first, alts


def _trousers(reading, m: Measurements, meas: dict) -> tuple[Design, list[Design]]:
    """Trousers of the read length (with back waist darts where the reading decided them: cut to
    the hips), then under a waistband, then with flared legs; the legs keep
    their own hem, not the read openings' (docs/decisions/024-hems-read-off-the-target.md)."""
    length = _hem_length(reading, m)
    g = reading.garment
    leg = "shorts" if g == "shorts" else _LEG.get(reading.length, "full")
    first = Design(garment=g, leg=leg, length=length, darts=bool(reading.darts))
    return first, [first.replace(waistband=True), first.replace(hem_flare=0.05)]


def _jumpsuit(reading, m: Measurements, meas: dict) -> tuple[Design, list[Design]]:
    """A bodice as read on trousers of the read length (their own hem, as :func:`_trousers`'); the
    sleeves' alternatives, then the neighbouring leg."""
    length = _hem_length(reading, m)
    leg = _LEG.get(reading.length, "full")
    first = Design(garment="jumpsuit", leg=leg, length=length, **_top_fields(reading, m, meas))
    return first, _top_alternatives(first, reading) + [first.replace(hem_flare=0.05)]


_BUILDERS = {
    "tshirt": _tshirt,
    "dress": _dress,
    "skirt": _skirt_garment,
    "pants": _trousers,
    "shorts": _trousers,
    "jumpsuit": _jumpsuit,
}


def _cuttable(d: Design, m: Measurements) -> Design | None:
    """``d`` when it drafts for ``m``; else ``d`` at its garment's own length when that drafts
    (a read length too short for its style); else None."""
    for cand in (d, d.replace(length=None)):
        try:
            draft(cand, m)
            return cand
        except InputError:
            continue
    return None


def design_candidates(
    reading, measurements: Measurements | None = None, *, measures: dict | None = None
) -> list[tuple[str, Design]]:
    """Up to :data:`MAX_CANDIDATES` (name, :class:`~unsew.pattern.design.Design`) consistent with
    ``reading`` (a :class:`~unsew.grading.design_reading.DesignReading`) and the target's
    ``measures`` (:func:`read_measures`; none: the garments' own hems), the design as read first,
    each one that drafts for ``measurements`` (default: the default body), distinct, named by
    :func:`~unsew.pattern.design.design_name`. Raises InputError for a garment type the design
    space has no designs of."""
    if reading.garment not in GARMENTS:
        raise InputError(f"no designs of a {reading.garment}; the design space drafts {', '.join(GARMENTS)}")
    m = measurements or Measurements()
    first, alts = _BUILDERS[reading.garment](reading, m, measures or {})
    out: list[tuple[str, Design]] = []
    for d in [first, *alts]:
        d = _cuttable(d, m)
        if d is not None and all(d != o for _, o in out):
            out.append((design_name(d), d))
        if len(out) == MAX_CANDIDATES:
            break
    return out


def drafted_candidates(reading, measurements: Measurements | None = None, *, measures=None) -> dict:
    """{name: Pattern}: :func:`design_candidates` drafted for ``measurements``, in order."""
    return {
        name: draft(d, measurements)
        for name, d in design_candidates(reading, measurements, measures=measures)
    }
