"""The panel measurements a pattern maker reads off a pattern: hem, side seam, sleeve, inseam and
waist lengths, found by the edge labels of GarmentCode patterns (``hem``, ``right_side``,
``right_underarm``, ``inseam``, ``waist``, ...), and the report's table of them for the base,
graded, final and true patterns."""

from __future__ import annotations

from typing import Sequence

from unsew.pattern.curves import edge_length

__all__ = ["panel_measurements", "measurement_table", "MEASUREMENTS"]

#: The measurements in table order, with what each one is.
MEASUREMENTS = {
    "hem": "hem girth: the hem edges of the body panels (one leg for trousers)",
    "side seam": "one side seam: right_side edges (outseam for trousers) of the first body panel",
    "sleeve": "sleeve underarm seam: the right_underarm edge of the first sleeve",
    "inseam": "inseam: the inseam edge of the first trouser panel",
    "waist": "waist girth: every waist edge",
}

_SIDE = ("right_side", "outseam_upper", "outseam_lower")


def _edges(panel, labels) -> list[int]:
    return [i for i, e in enumerate(panel.edges) if e.label in labels]


def panel_measurements(pattern) -> dict[str, float]:
    """The measurements of :data:`MEASUREMENTS` that ``pattern`` has, in metres (arc lengths of
    its edges, curves included). A pattern whose edges carry no such labels gives ``{}``."""
    panels = [pattern.panels[n] for n in pattern.panel_order if n in pattern.panels] or list(pattern.panels.values())
    sleeves = [p for p in panels if "sleeve" in p.name]
    body = [p for p in panels if "sleeve" not in p.name]
    legs = [p for p in body if p.name.startswith("left_")]
    out: dict[str, float] = {}

    def total(ps, labels) -> float:
        return float(sum(edge_length(p, i) for p in ps for i in _edges(p, labels)))

    hem = total(legs if legs and any(_edges(p, ("inseam",)) for p in legs) else body, ("hem",))
    if hem > 0:
        out["hem"] = hem
    for p in body:
        side = total([p], _SIDE)
        if side <= 0:
            plain = [edge_length(p, i) for i in _edges(p, ("side", "left_side"))]
            side = max(plain, default=0.0)
        if side > 0:
            out["side seam"] = float(side)
            break
    for p in sleeves:
        idx = _edges(p, ("right_underarm", "underarm"))
        if idx:
            out["sleeve"] = float(edge_length(p, idx[0]))
            break
    for p in body:
        idx = _edges(p, ("inseam",))
        if idx:
            out["inseam"] = float(edge_length(p, idx[0]))
            break
    waist = total(body, ("waist",))
    if waist > 0:
        out["waist"] = waist
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
