"""The panel measurements a pattern maker reads off a pattern: hem, side seam, sleeve, inseam and
waist lengths, found by the edge labels of GarmentCode patterns (``hem``, ``right_side``,
``right_underarm``, ``inseam``, ``waist``, ...), the girths the pattern gives the body (chest at
the armhole's foot, sleeve at the underarm), and the report's tables of them for the base,
graded, final and true patterns; and the length of every seam on both its sides
(:func:`seam_table`)."""

from __future__ import annotations

from typing import Sequence

import numpy as np

from unsew.pattern.curves import edge_length

__all__ = ["panel_measurements", "measurement_table", "seam_table", "MEASUREMENTS"]

#: The measurements in table order, with what each one is.
MEASUREMENTS = {
    "hem": "hem girth: the hem edges of the body panels (one leg for trousers)",
    "side seam": "one side seam: right_side edges (outseam for trousers) of the first body panel",
    "sleeve": "sleeve underarm seam: the right_underarm edge of the first sleeve",
    "inseam": "inseam: the inseam edge of the first trouser panel",
    "waist": "waist girth: every waist edge (or, open, the lower_interface edges a lower garment hangs from)",
    "chest girth": "chest girth: the body panels' widths at the foot of the armhole, summed",
    "sleeve girth": "sleeve girth at the underarm: the first sleeve's width where underarm seam and cap meet",
}

_SIDE = ("right_side", "outseam_upper", "outseam_lower")


def _edges(panel, labels) -> list[int]:
    return [i for i, e in enumerate(panel.edges) if e.label in labels]


def _total(ps, labels) -> float:
    """Summed arc length [m] of the edges of panels ``ps`` labelled one of ``labels``."""
    return float(sum(edge_length(p, i) for p in ps for i in _edges(p, labels)))


def _first_edge_length(ps, labels) -> float | None:
    """Arc length [m] of the first edge labelled one of ``labels`` on the first panel of ``ps``
    that has one (None if none has)."""
    for p in ps:
        idx = _edges(p, labels)
        if idx:
            return float(edge_length(p, idx[0]))
    return None


def _side_seam(body) -> float | None:
    """One side seam [m]: the right_side (outseam) edges of the first body panel that has them,
    else its longest plain side edge (None if no panel has either)."""
    for p in body:
        side = _total([p], _SIDE)
        if side <= 0:
            plain = [edge_length(p, i) for i in _edges(p, ("side", "left_side"))]
            side = max(plain, default=0.0)
        if side > 0:
            return float(side)
    return None


def _chest_girth(body) -> float:
    """The body panels' widths [m] at the foot of their armholes, summed (0 without armholes)."""
    chest = 0.0
    for p in body:
        arm = _edges(p, ("right_armhole", "left_armhole", "armhole"))
        if arm:
            foot = min(min(p.vertices[p.edges[i].start][1], p.vertices[p.edges[i].end][1]) for i in arm)
            chest += _width_at(p, foot + 1e-6)
    return chest


def _sleeve_girth(sleeves) -> float | None:
    """The first sleeve's width [m] where its underarm seam meets the cap (None without one)."""
    for p in sleeves:
        under = _edges(p, ("right_underarm", "underarm"))
        if under:
            e = p.edges[under[0]]
            y = max(p.vertices[e.start][1], p.vertices[e.end][1])
            return float(_width_at(p, y - 1e-6))
    return None


def panel_measurements(pattern) -> dict[str, float]:
    """The measurements of :data:`MEASUREMENTS` that ``pattern`` has, in metres (arc lengths of
    its edges, curves included). A pattern whose edges carry no such labels gives ``{}``."""
    panels = [pattern.panels[n] for n in pattern.panel_order if n in pattern.panels] or list(
        pattern.panels.values()
    )
    sleeves = [p for p in panels if "sleeve" in p.name]
    body = [p for p in panels if "sleeve" not in p.name]
    legs = [p for p in body if p.name.startswith("left_")]
    hem = _total(legs if legs and any(_edges(p, ("inseam",)) for p in legs) else body, ("hem",))
    waist, chest = _total(body, ("waist",)) or _total(body, ("lower_interface",)), _chest_girth(body)
    found = {  # None: the pattern does not have it
        "hem": hem if hem > 0 else None,
        "side seam": _side_seam(body),
        "sleeve": _first_edge_length(sleeves, ("right_underarm", "underarm")),
        "inseam": _first_edge_length(body, ("inseam",)),
        "waist": waist if waist > 0 else None,
        "chest girth": float(chest) if chest > 0 else None,
        "sleeve girth": _sleeve_girth(sleeves),
    }
    return {k: v for k, v in found.items() if v is not None}


def _width_at(panel, y: float) -> float:
    """Total width [m] of ``panel`` along the horizontal line at height ``y`` (its outline's
    crossings, paired)."""
    from unsew.pattern.curves import panel_outline

    poly = panel_outline(panel, points_per_edge=64)
    a, b = poly, np.roll(poly, -1, axis=0)
    m = (a[:, 1] - y) * (b[:, 1] - y) < 0
    if not m.any():
        return 0.0
    t = (y - a[m, 1]) / (b[m, 1] - a[m, 1])
    xs = np.sort(a[m, 0] + t * (b[m, 0] - a[m, 0]))
    return float(sum(xs[i + 1] - xs[i] for i in range(0, len(xs) - 1, 2)))


def seam_table(pattern) -> dict[str, dict]:
    """The length of every seam on both its sides: ``{"A": {"side a": "front: right_side",
    "a [cm]": 52.1, "side b": "back: left_side", "b [cm]": 52.1, "difference [mm]": 0.0}, ...}``,
    seams named by the codes the SVG, DXF and PDF print (A, B, ...); lengths are arc lengths of
    the sew line."""
    from unsew.io.sheet import stitch_code

    out = {}
    for k, st in enumerate(pattern.stitches):
        pa, pb = pattern.panels[st.a.panel], pattern.panels[st.b.panel]
        la, lb = edge_length(pa, st.a.edge), edge_length(pb, st.b.edge)
        out[stitch_code(k)] = {
            "side a": f"{st.a.panel}: {pa.edges[st.a.edge].label or 'edge ' + str(st.a.edge)}",
            "a [cm]": round(100.0 * la, 2),
            "side b": f"{st.b.panel}: {pb.edges[st.b.edge].label or 'edge ' + str(st.b.edge)}",
            "b [cm]": round(100.0 * lb, 2),
            "difference [mm]": round(1000.0 * (la - lb), 1) + 0.0,  # no "-0"
        }
    return out


def measurement_table(patterns: Sequence[tuple[str, object]]) -> list[dict]:
    """Rows ``{"measurement": name, "<label> [cm]": value, ...}`` for each measurement that at
    least one of ``patterns`` ((label, Pattern) pairs, e.g. base, graded, final, true) has;
    a pattern without it gets None. Lengths in centimetres, rounded to 0.1 mm. Columns in the
    order base, graded, final, true, then any other label."""
    order = {"base": 0, "graded": 1, "final": 2, "true": 3}
    ps = sorted(((str(label), p) for label, p in patterns), key=lambda lp: order.get(lp[0], len(order)))
    measured = [(label, panel_measurements(p)) for label, p in ps if hasattr(p, "panels")]
    rows = []
    for name in MEASUREMENTS:
        if not any(name in m for _, m in measured):
            continue
        row: dict = {"measurement": name}
        for label, m in measured:
            row[f"{label} [cm]"] = round(100.0 * m[name], 2) if name in m else None
        rows.append(row)
    return rows
