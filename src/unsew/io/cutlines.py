"""Cut lines, seam allowances and cutting notes of a sewing pattern, shared by the SVG, DXF and
PDF writers.

A panel's outline in a pattern is its *sew line* (the seam itself). A workroom cuts along the
*cut line*: the sew line offset outward by the seam allowance of each edge (default
:data:`SEAM_ALLOWANCE_M`, edges labelled ``hem`` :data:`HEM_ALLOWANCE_M`; in a pattern without
such labels, each panel's lowest free edge on the body, :func:`_guess_hems`). Each edge's offset
lines are joined by their intersection (a mitre); a convex corner whose mitre would reach
further than :data:`MITER_LIMIT` allowances from the sew corner is clipped square to the
bisector there, and the small loops an outward offset makes in a concave corner are cut away.

Per-edge overrides live in the pattern's ``unsew`` key (metres)::

    "seam_allowance": {"default_m": 0.01, "hem_m": 0.02,
                       "panels": {"front": {"neckline": 0.006, "3": 0.015}}}

where a panel's entries are keyed by an edge label (all edges with that label) or an edge index
(as a string); an index wins over a label, a label over the defaults.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from unsew.errors import InputError
from unsew.pattern.curves import edge_length, sample_edge
from unsew.pattern.model import Pattern

__all__ = [
    "SEAM_ALLOWANCE_M",
    "HEM_ALLOWANCE_M",
    "MITER_LIMIT",
    "PieceLines",
    "seam_allowances",
    "piece_lines",
    "offset_polygon",
    "cutting_notes",
    "CuttingNote",
]

#: Seam allowance of an edge [m] unless set otherwise; of edges labelled ``hem`` [m].
SEAM_ALLOWANCE_M = 0.01
HEM_ALLOWANCE_M = 0.02
#: A convex corner's mitre is clipped where it reaches further than this many allowances from the
#: sew-line corner.
MITER_LIMIT = 2.0
#: Maximum distance between polyline points along curved edges [m].
CURVE_STEP = 0.001


def _is_hem(label: str) -> bool:
    return "hem" in (label or "").lower()


def seam_allowances(
    pattern: Pattern, *, default: float | None = None, hem: float | None = None
) -> dict[str, np.ndarray]:
    """Seam allowance [m] of each edge of each panel: {panel name: (E,) float64}.

    default, hem: allowance of plain and hem edges [m]; None takes the pattern's
    ``unsew.seam_allowance`` ``default_m`` / ``hem_m``, else :data:`SEAM_ALLOWANCE_M` /
    :data:`HEM_ALLOWANCE_M`. Per-edge entries of the pattern's key override both. Raises
    InputError on a negative, non-finite or over 10 cm allowance, or an override naming no edge."""
    spec = (pattern.unsew or {}).get("seam_allowance") or {}
    if not isinstance(spec, dict):
        raise InputError("the pattern's unsew.seam_allowance must be an object {default_m, hem_m, panels}")
    d = float(spec.get("default_m", SEAM_ALLOWANCE_M)) if default is None else float(default)
    h = float(spec.get("hem_m", HEM_ALLOWANCE_M)) if hem is None else float(hem)
    overrides = spec.get("panels") or {}
    labelled = any(_is_hem(e.label) for pan in pattern.panels.values() for e in pan.edges)
    guessed = {} if labelled else _guess_hems(pattern)
    out = {}
    for name in pattern.panel_order:
        pan = pattern.panels[name]
        w = np.array(
            [h if _is_hem(e.label) or (name, i) in guessed else d for i, e in enumerate(pan.edges)],
            dtype=np.float64,
        )
        ov = overrides.get(name) or {}
        for key in sorted(ov, key=lambda k: str(k).isdigit()):  # labels first, indices win
            hit = [int(key)] if str(key).isdigit() else [i for i, e in enumerate(pan.edges) if e.label == key]
            if not hit or hit[0] >= len(pan.edges):
                raise InputError(
                    f"seam allowance for panel {name!r}: {key!r} is neither an edge label nor an "
                    f"edge index (0..{len(pan.edges) - 1}) of that panel"
                )
            w[hit] = float(ov[key])
        out[name] = w
    for name, w in out.items():
        if not np.all(np.isfinite(w)) or (w < 0).any() or (w > 0.1).any():
            raise InputError(
                f"seam allowance of panel {name!r} must lie in 0..10 cm, got "
                f"{', '.join(f'{100 * x:g}' for x in w)} cm"
            )
    return out


def _guess_hems(pattern: Pattern) -> set[tuple[str, int]]:
    """Hems of a pattern whose edges carry no ``hem`` label (GarmentCode's own patterns label no
    edges): on each panel, the free (unstitched) edge lowest on the body in its 3D placement,
    when its middle lies below the panel's middle (a neckline or waist, at the top, never is).
    Returns {(panel name, edge index)}."""
    sewn = {(s.a.panel, s.a.edge) for s in pattern.stitches} | {
        (s.b.panel, s.b.edge) for s in pattern.stitches
    }
    out = set()
    for name, pan in pattern.panels.items():
        free = [i for i in range(len(pan.edges)) if (name, i) not in sewn]
        if not free:
            continue
        try:
            mids = {i: float(pan.to_world(sample_edge(pan, i, 8)[4][None])[0, 1]) for i in free}
            middle = float(pan.to_world(np.asarray(pan.vertices, dtype=np.float64))[:, 1].mean())
        except Exception:  # a panel without a usable placement: no guess
            continue
        low = min(mids, key=mids.get)
        if mids[low] < middle:
            out.add((name, low))
    return out


@dataclass
class PieceLines:
    """The lines of one piece in its panel frame [m].

    sew: closed sew line (M, 2) float64 (the panel outline, curves sampled at most
    :data:`CURVE_STEP` apart, last point not repeated); sew_edge: (M,) int64, the edge each
    segment sew[j] -> sew[j+1] belongs to. cut: closed cut line (K, 2) float64; cut_corner:
    (K,) bool, cut points where one edge's allowance ends (the turn points). allowance: (E,)
    float64 [m] per edge."""

    sew: np.ndarray
    sew_edge: np.ndarray
    cut: np.ndarray
    cut_corner: np.ndarray
    allowance: np.ndarray


def sew_line(panel, *, step: float = CURVE_STEP) -> tuple[np.ndarray, np.ndarray]:
    """The panel's closed outline (M, 2) [m] and the edge index (M,) of each segment from point j."""
    pts, eid = [], []
    for i, e in enumerate(panel.edges):
        n = 1 if e.curvature is None else max(8, int(np.ceil(edge_length(panel, i) / step)))
        pts.append(sample_edge(panel, i, n)[:-1])
        eid.append(np.full(n, i, dtype=np.int64))
    return np.concatenate(pts), np.concatenate(eid)


def piece_lines(panel, allowance: np.ndarray, *, step: float = CURVE_STEP) -> PieceLines:
    """Sew and cut lines of ``panel`` (counter-clockwise) with per-edge ``allowance`` (E,) [m]."""
    sew, eid = sew_line(panel, step=step)
    cut, corner = offset_polygon(sew, np.asarray(allowance, dtype=np.float64)[eid], eid)
    return PieceLines(sew, eid, cut, corner, np.asarray(allowance, dtype=np.float64))


def offset_polygon(
    pts: np.ndarray, width: np.ndarray, group: np.ndarray | None = None
) -> tuple[np.ndarray, np.ndarray]:
    """Offset the closed counter-clockwise polygon ``pts`` (M, 2) [m] outward, segment j (pts[j] ->
    pts[j+1]) by ``width[j]`` [m] (M,).

    Consecutive offset segments are joined at their lines' intersection; a convex join whose
    intersection lies further than :data:`MITER_LIMIT` times the larger width from the polygon
    point is clipped perpendicular to that direction (two points); a concave one so far (two
    widths meeting almost in line) steps from one offset to the other. Loops the offset makes in
    concave stretches are then removed. ``group`` (M,) labels segments (the edge index); a join
    between two groups is flagged as a corner. Returns (points (K, 2), corner (K,) bool)."""
    p = np.asarray(pts, dtype=np.float64)
    w = np.asarray(width, dtype=np.float64)
    g = np.zeros(len(p), dtype=np.int64) if group is None else np.asarray(group)
    d = np.roll(p, -1, axis=0) - p
    t = d / np.linalg.norm(d, axis=1, keepdims=True)
    nrm = np.stack([t[:, 1], -t[:, 0]], axis=1)  # right of the direction: outward for CCW
    a = p + w[:, None] * nrm  # offset segment j starts at a[j] with direction t[j]
    ap, tp, wp = np.roll(a, 1, axis=0), np.roll(t, 1, axis=0), np.roll(w, 1)  # the segment before
    cross = tp[:, 0] * t[:, 1] - tp[:, 1] * t[:, 0]
    diff = a - ap
    with np.errstate(divide="ignore", invalid="ignore"):
        s = (diff[:, 0] * t[:, 1] - diff[:, 1] * t[:, 0]) / cross
    x = ap + s[:, None] * tp
    lim = MITER_LIMIT * np.maximum(np.maximum(w, wp), 1e-9)
    reach = np.linalg.norm(x - p, axis=1)
    corner_join = g != np.roll(g, 1)
    out, flag = [], []
    for j in range(len(p)):
        if np.isfinite(reach[j]) and reach[j] <= lim[j] and abs(cross[j]) > 1e-12:
            out.append(x[j])
            flag.append(corner_join[j])
        elif abs(w[j] - wp[j]) < 1e-12 and abs(cross[j]) <= 1e-12:  # in line, same width
            out.append(p[j] + w[j] * nrm[j])
            flag.append(corner_join[j])
        elif cross[j] > 0:  # convex: clip the mitre square to the bisector at the limit
            u = x[j] - p[j] if np.isfinite(reach[j]) else (nrm[j] + np.roll(nrm, 1, axis=0)[j])
            u = u / np.linalg.norm(u)
            for base, tt in ((ap[j], tp[j]), (a[j], t[j])):
                den = tt @ u
                k = (lim[j] - (base - p[j]) @ u) / den if abs(den) > 1e-12 else 0.0
                out.append(base + k * tt)
                flag.append(corner_join[j])
        else:  # concave, or in line with different widths: step from one offset to the other
            out += [p[j] + wp[j] * np.roll(nrm, 1, axis=0)[j], a[j]]
            flag += [corner_join[j], corner_join[j]]
    return _remove_loops(np.asarray(out), np.asarray(flag, dtype=bool))


def _seg_hits(q: np.ndarray) -> tuple[int, int, np.ndarray] | None:
    """The crossing of two non-adjacent segments of the closed polyline ``q`` (K, 2) that cuts
    off the fewest points: (i, k, crossing point) with i < k, or None."""
    n = len(q)
    a, b = q, np.roll(q, -1, axis=0)
    lo, hi = np.minimum(a, b), np.maximum(a, b)
    best = None
    for i0 in range(0, n, 256):
        i = np.arange(i0, min(n, i0 + 256))
        # box overlap first (cheap), then the exact test on the candidates
        ov = (
            (lo[i, None, 0] <= hi[None, :, 0])
            & (lo[None, :, 0] <= hi[i, None, 0])
            & (lo[i, None, 1] <= hi[None, :, 1])
            & (lo[None, :, 1] <= hi[i, None, 1])
        )
        ii, kk = np.nonzero(ov)
        ii = i[ii]
        keep = (kk > ii + 1) & ~((ii == 0) & (kk == n - 1))
        ii, kk = ii[keep], kk[keep]
        if not len(ii):
            continue
        r, s = b[ii] - a[ii], b[kk] - a[kk]
        den = r[:, 0] * s[:, 1] - r[:, 1] * s[:, 0]
        qp = a[kk] - a[ii]
        with np.errstate(divide="ignore", invalid="ignore"):
            tt = (qp[:, 0] * s[:, 1] - qp[:, 1] * s[:, 0]) / den
            uu = (qp[:, 0] * r[:, 1] - qp[:, 1] * r[:, 0]) / den
        hit = (np.abs(den) > 1e-15) & (tt > 0) & (tt < 1) & (uu > 0) & (uu < 1)
        # segments along one line overlapping (two offset edges meeting head on): the start of
        # segment k inside segment i counts as their crossing
        rr = (r * r).sum(1)
        line = (np.abs(den) <= 1e-15) & (
            np.abs(qp[:, 0] * r[:, 1] - qp[:, 1] * r[:, 0]) <= 1e-12 * np.sqrt(rr)
        )
        tc = (qp * r).sum(1) / rr
        on = line & (tc > 0) & (tc < 1)
        tt = np.where(on, tc, tt)
        for m in np.nonzero(hit | on)[0]:
            span = min(kk[m] - ii[m], n - (kk[m] - ii[m]))
            if best is None or span < best[0]:
                best = (span, int(ii[m]), int(kk[m]), a[ii[m]] + tt[m] * r[m])
    return None if best is None else best[1:]


def _remove_loops(q: np.ndarray, flag: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Cut the self-crossing loops out of the closed polyline ``q``, the smaller side each time."""
    for _ in range(len(q)):
        hit = _seg_hits(q)
        if hit is None:
            break
        i, k, x = hit
        if k - i <= len(q) - (k - i):  # drop points i+1..k, put the crossing in their place
            q = np.concatenate([q[: i + 1], x[None], q[k + 1 :]])
            flag = np.concatenate([flag[: i + 1], [bool(flag[i + 1 : k + 1].any())], flag[k + 1 :]])
        else:  # drop points k+1.. and ..i
            q = np.concatenate([x[None], q[i + 1 : k + 1]])
            flag = np.concatenate([[bool(flag[k + 1 :].any() or flag[: i + 1].any())], flag[i + 1 : k + 1]])
    return q, flag


@dataclass
class CuttingNote:
    """What the workroom cuts of one piece: ``quantity`` pieces; ``text`` the human line
    ('cut 1', 'cut 1; mirror of right_front; (as a pair: cut 2 from doubled fabric)', 'cut 1 on fold
    (...)'; parts after '; ' are printed on lines of their own); ``fold``: for a piece symmetric about a line,
    (point (2,), unit direction (2,)) [m] in the panel frame, else None."""

    quantity: int
    text: str
    fold: tuple[np.ndarray, np.ndarray] | None = None


def cutting_notes(pattern: Pattern) -> dict[str, CuttingNote]:
    """The cutting note of every panel from the pattern's symmetry (its ``unsew.symmetry`` when
    present, else detected): a panel mirroring another is one of a mirrored pair; a panel
    symmetric about a line may be cut on the fold there. Every panel is drawn, so each is
    'cut 1' and the note says how the pieces relate."""
    sym = (pattern.unsew or {}).get("symmetry")
    pairs, mirrors = [], []
    if isinstance(sym, dict) and "pairs" in sym:
        pairs = [(q["source"], q["target"], bool(q.get("mirrored"))) for q in sym.get("pairs", [])]
        mirrors = [
            (m["panel"], np.asarray(m["point"], float), np.asarray(m["direction"], float))
            for m in sym.get("mirrors", [])
        ]
    else:
        try:
            from unsew.pattern.symmetry import detect_symmetry

            s = detect_symmetry(pattern)
            pairs = [(q.source, q.target, bool(q.mirrored)) for q in s.pairs]
            mirrors = [
                (m.panel, np.asarray(m.point, float), np.asarray(m.direction, float)) for m in s.mirrors
            ]
        except Exception:  # a pattern symmetry cannot be found for is still exported, note-less
            pass
    folds = {name: (point, direction / np.linalg.norm(direction)) for name, point, direction in mirrors}
    partner = {}
    for src, dst, mirrored in pairs:
        if src in pattern.panels and dst in pattern.panels:
            partner[src], partner[dst] = (dst, mirrored), (src, mirrored)
    notes = {}
    for n in pattern.panel_order:
        fold = folds.get(n)
        text = "cut 1 on fold (fold line marked), or whole as drawn" if fold is not None else "cut 1"
        if n in partner:
            other, mirrored = partner[n]
            alike = not mirrored or fold is not None or other in folds  # a symmetric piece's mirror is itself
            text += (
                f"; same shape as {other}"
                if alike
                else f"; mirror of {other}; (as a pair: cut 2 from doubled fabric)"
            )
        notes[n] = CuttingNote(1, text, fold)
    return notes
