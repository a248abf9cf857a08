"""GarmentCode specification JSON: read and write sewing patterns losslessly.

The file (GarmentCode's ``specification.json``)::

    {"pattern": {"panels": {name: {"translation": [x, y, z], "rotation": [rx, ry, rz],
                                   "vertices": [[x, y], ...], "edges": [...], "label": ...}},
                 "stitches": [[{"panel": name, "edge": i}, {"panel": name, "edge": j}], ...],
                 "panel_order": [...]},
     "properties": {"units_in_meter": 100, "curvature_coords": "relative", ...},
     "unsew": {"format_version": 1, "name": ..., ...}}

Lengths in the file (vertices, translations, circle radii) are in ``1/units_in_meter`` m (cm
when 100); they become metres here and only here. Rotations are XYZ Euler angles [deg].
Edge curvature is ``{"type": "quadratic"|"cubic"|"circle", "params": ...}``; older files write
``"curvature": [x, y]`` (a quadratic) and may use ``"curvature_coords": "absolute"`` (control
points in panel coordinates): both are read, and the pattern keeps relative coordinates (its
``properties["curvature_coords"]`` says ``"relative"`` after loading). Circle params are
``[radius, large_arc, right]`` (see :mod:`unsew.pattern.model`).

Everything else the file carries (extra keys of panels, edges, curvature, stitch sides, stitch
entries after the two sides, top-level keys such as ``parameters``) is kept and written back.
unsew's additions live under the top-level ``"unsew"`` key, which GarmentCode ignores.
"""

from __future__ import annotations

import json
import math
import os
from pathlib import Path

import numpy as np

from unsew.errors import InputError, PatternError
from unsew.pattern.model import Curvature, Edge, Panel, Pattern, Stitch, StitchSide

__all__ = ["load_pattern", "save_pattern", "pattern_from_dict", "pattern_to_dict", "FORMAT_VERSION"]

#: Version of the ``"unsew"`` block this module writes.
FORMAT_VERSION = 1

_PANEL_KEYS = ("translation", "rotation", "vertices", "edges", "label")
_EDGE_KEYS = ("endpoints", "curvature", "label")


def _number(x, where: str) -> float:
    if isinstance(x, bool) or not isinstance(x, (int, float)):
        raise InputError(f"{where}: expected a number, got {x!r}; fix the pattern file")
    return float(x)


def _points(x, where: str, dim: int) -> np.ndarray:
    """A list of 2D points, shape (N, 2) (``dim == 2``), or a vector of ``-dim`` numbers
    (``dim < 0``: ``-3`` for a translation, ``-2`` for one point), as float64."""
    try:
        a = np.asarray(x, dtype=np.float64)
    except (TypeError, ValueError):
        raise InputError(f"{where}: expected numbers; fix the pattern file") from None
    if dim == 2:
        if a.size == 0:
            return a.reshape(0, 2)
        if a.ndim != 2 or a.shape[1] != 2:
            raise InputError(f"{where}: expected a list of [x, y] points; fix the pattern file")
    elif a.shape != (-dim,):
        raise InputError(f"{where}: expected {-dim} numbers; fix the pattern file")
    return a


def _rel(a: np.ndarray, b: np.ndarray, p) -> list[float]:
    from unsew.pattern.curves import absolute_to_relative

    if float(np.linalg.norm(b - a)) == 0.0:
        raise PatternError("zero-length curved edge: its control points cannot be made relative")
    st = absolute_to_relative(a, b, np.asarray(p, dtype=np.float64))
    return [float(st[0]), float(st[1])]


def _curvature_from(
    c, a: np.ndarray, b: np.ndarray, absolute: bool, scale: float, where: str
) -> Curvature | None:
    """File curvature -> model Curvature (relative, metres). ``a``, ``b``: edge ends [m]."""
    if c is None:
        return None
    if isinstance(c, list):  # legacy: one quadratic control point
        p = _points(c, f"{where} legacy curvature [x, y]", -2)
        st = _rel(a, b, p / scale) if absolute else [float(p[0]), float(p[1])]
        return Curvature("quadratic", [st])
    if not isinstance(c, dict) or "type" not in c:
        raise InputError(
            f"{where}: curvature must be {{'type': ..., 'params': ...}} or [x, y]; fix the pattern file"
        )
    kind, params = c["type"], c.get("params")
    extra = {k: v for k, v in c.items() if k not in ("type", "params")}
    if kind in ("quadratic", "cubic"):
        n = 1 if kind == "quadratic" else 2
        pts = _points(params, f"{where} {kind} params", 2)
        if len(pts) != n:
            raise InputError(f"{where}: a {kind} curve needs {n} control point(s), got {len(pts)}")
        if absolute:
            out = [_rel(a, b, q / scale) for q in pts]
        else:
            out = [[float(q[0]), float(q[1])] for q in pts]
        return Curvature(kind, out, extra)
    if kind == "circle":
        if not isinstance(params, list) or len(params) != 3:
            raise InputError(f"{where}: circle params must be [radius, large_arc, right]")
        r = _number(params[0], f"{where} circle radius") / scale
        return Curvature("circle", [r, bool(params[1]), bool(params[2])], extra)
    raise InputError(f"{where}: unknown curvature type {kind!r} (quadratic, cubic or circle)")


def _curvature_to(c: Curvature, scale: float) -> dict:
    if c.kind == "circle":
        r, large, right = c.params
        params = [float(r) * scale, int(bool(large)), int(bool(right))]
    else:
        params = [[float(s), float(t)] for s, t in c.params]
    return {"type": c.kind, "params": params, **c.extra}


def pattern_from_dict(data: dict, *, name: str = "pattern", validate: bool = True) -> Pattern:
    """Build a :class:`Pattern` [m] from a parsed GarmentCode specification dict.

    ``name`` is used when the dict carries no ``unsew.name``. With ``validate`` the pattern is
    checked and normalized (clockwise panels reoriented) by
    :func:`unsew.pattern.validate.validate_pattern`, which raises
    :class:`~unsew.errors.PatternError`; its warnings go to ``warnings.warn`` (category
    ``UserWarning``). Malformed structure raises :class:`~unsew.errors.InputError`.
    """
    if not isinstance(data, dict) or not isinstance(data.get("pattern"), dict):
        raise InputError("not a GarmentCode specification: the top level needs a 'pattern' object")
    pat = data["pattern"]
    panels_in = pat.get("panels")
    if not isinstance(panels_in, dict):
        raise InputError("not a GarmentCode specification: 'pattern.panels' must be an object of panels")
    props, absolute, scale = _properties_from_dict(data)
    panels = {pname: _panel_from_dict(pname, pd, absolute, scale) for pname, pd in panels_in.items()}
    stitches = [_stitch_from_list(k, st) for k, st in enumerate(pat.get("stitches") or [])]

    uns = dict(data.get("unsew") or {})
    uns.pop("format_version", None)
    uns.pop("units", None)
    pname = uns.pop("name", name)
    for s, lab in zip(stitches, uns.pop("stitch_labels", [])):
        s.label = lab
    order = pat.get("panel_order") or list(panels)
    missing = [n for n in order if n not in panels]
    if missing:
        raise PatternError(f"panel_order names missing panel(s) {missing}; fix panel_order or add the panels")
    order += [n for n in panels if n not in order]
    extra_top = {k: v for k, v in data.items() if k not in ("pattern", "properties", "unsew")}
    pattern_extra = {k: v for k, v in pat.items() if k not in ("panels", "stitches", "panel_order")}
    if pattern_extra:
        extra_top["_pattern"] = pattern_extra
    p = Pattern(pname, panels, stitches, list(order), props, uns, extra_top)
    if validate:
        from unsew.pattern.validate import validate_pattern

        import warnings

        for msg in validate_pattern(p):
            warnings.warn(msg, stacklevel=2)
    return p


def _properties_from_dict(data: dict) -> tuple[dict, bool, float]:
    """The specification's ``properties``, checked: (properties as the model keeps them,
    whether the file's curvature coordinates are absolute, file units per metre: 100 for cm)."""
    props = dict(data.get("properties") or {})
    if not isinstance(data.get("properties", {}), dict):
        raise InputError("'properties' must be an object")
    units = props.get("units_in_meter", 100)
    if (
        isinstance(units, bool)
        or not isinstance(units, (int, float))
        or not math.isfinite(units)
        or units <= 0
    ):
        raise InputError(f"properties.units_in_meter must be a positive number (100 for cm), got {units!r}")
    coords = props.get("curvature_coords", "relative")
    if coords not in ("relative", "absolute"):
        raise InputError(f"properties.curvature_coords must be 'relative' or 'absolute', got {coords!r}")
    props["curvature_coords"] = "relative"  # the model always holds relative coordinates
    props["units_in_meter"] = units  # the unit this pattern is written in again
    return props, coords == "absolute", float(units)


def _panel_from_dict(pname: str, pd, absolute: bool, scale: float) -> Panel:
    """One panel of the file, vertices and translation divided by ``scale`` (file units per
    metre) into [m], rotation in [deg]; unknown keys kept in ``extra``."""
    w = f"panel {pname!r}"
    if not isinstance(pd, dict):
        raise InputError(f"{w}: must be an object with vertices and edges")
    if "vertices" not in pd or "edges" not in pd:
        raise InputError(f"{w}: needs 'vertices' and 'edges'")
    verts = _points(pd["vertices"], f"{w} vertices", 2) / scale
    tr = _points(pd.get("translation", [0, 0, 0]), f"{w} translation", -3) / scale
    rot = _points(pd.get("rotation", [0, 0, 0]), f"{w} rotation", -3)
    if not isinstance(pd["edges"], list):
        raise InputError(f"{w}: 'edges' must be a list")
    edges = [_edge_from_dict(ed, verts, absolute, scale, f"{w} edge {i}") for i, ed in enumerate(pd["edges"])]
    extra = {k: v for k, v in pd.items() if k not in _PANEL_KEYS}
    return Panel(pname, verts, edges, tr, rot, pd.get("label", ""), extra)


def _edge_from_dict(ed, verts: np.ndarray, absolute: bool, scale: float, we: str) -> Edge:
    """One edge of a panel whose vertices ``verts`` (N, 2) [m] are read; ``we`` names it in
    error messages."""
    if not isinstance(ed, dict) or not isinstance(ed.get("endpoints"), list) or len(ed["endpoints"]) != 2:
        raise InputError(f"{we}: needs 'endpoints': [i, j]")
    s, e = ed["endpoints"]
    if not all(isinstance(k, int) and not isinstance(k, bool) for k in (s, e)):
        raise InputError(f"{we}: endpoints must be integer vertex indices")
    if not (0 <= s < len(verts) and 0 <= e < len(verts)):
        raise PatternError(f"{we}: endpoint out of range (panel has {len(verts)} vertices)")
    curv = _curvature_from(ed.get("curvature"), verts[s], verts[e], absolute, scale, we)
    extra = {k: v for k, v in ed.items() if k not in _EDGE_KEYS}
    return Edge(s, e, curv, ed.get("label", ""), extra)


def _stitch_from_list(k: int, st) -> Stitch:
    """Stitch ``k`` of the file, ``[{'panel': name, 'edge': index}, {...}, ...]``; anything
    else in it is kept in ``extra`` (its label comes later, from ``unsew.stitch_labels``)."""
    if not isinstance(st, list) or len(st) < 2 or not all(isinstance(x, dict) for x in st[:2]):
        raise InputError(f"stitch {k}: must be a list of two {{'panel': name, 'edge': index}} objects")
    sides, extra = [], {}
    for key, sd in zip("ab", st[:2]):
        if "panel" not in sd or "edge" not in sd:
            raise InputError(f"stitch {k}: each side needs 'panel' and 'edge'")
        if not isinstance(sd["edge"], int) or isinstance(sd["edge"], bool):
            raise InputError(f"stitch {k}: edge index must be an integer, got {sd['edge']!r}")
        sides.append(StitchSide(str(sd["panel"]), sd["edge"]))
        more = {x: v for x, v in sd.items() if x not in ("panel", "edge")}
        if more:
            extra[key] = more
    if len(st) > 2:
        extra["tail"] = list(st[2:])
    return Stitch(sides[0], sides[1], "", extra)


def _jsonable(x):
    if isinstance(x, np.ndarray):
        return x.tolist()
    if isinstance(x, (np.floating, np.integer, np.bool_)):
        return x.item()
    if isinstance(x, dict):
        return {k: _jsonable(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [_jsonable(v) for v in x]
    return x


def pattern_to_dict(pattern: Pattern) -> dict:
    """The GarmentCode specification dict of ``pattern`` (lengths written in
    ``1/units_in_meter`` m, 100 = cm unless the pattern's properties say otherwise)."""
    props = dict(pattern.properties)
    props.setdefault("units_in_meter", 100)
    props["curvature_coords"] = "relative"
    scale = float(props["units_in_meter"])
    panels = {}
    for name, p in pattern.panels.items():
        edges = []
        for e in p.edges:
            d = {"endpoints": [int(e.start), int(e.end)]}
            if e.curvature is not None:
                d["curvature"] = _curvature_to(e.curvature, scale)
            if e.label:
                d["label"] = e.label
            d.update(e.extra)
            edges.append(d)
        pd = {
            "translation": (p.translation * scale).tolist(),
            "rotation": p.rotation.tolist(),
            "vertices": (p.vertices * scale).tolist(),
            "edges": edges,
        }
        if p.label:
            pd["label"] = p.label
        pd.update(p.extra)
        panels[name] = pd
    stitches = []
    for s in pattern.stitches:
        entry = [
            {"panel": s.a.panel, "edge": int(s.a.edge), **s.extra.get("a", {})},
            {"panel": s.b.panel, "edge": int(s.b.edge), **s.extra.get("b", {})},
        ]
        entry += list(s.extra.get("tail", []))
        stitches.append(entry)
    extra = dict(pattern.extra)
    pat_extra = extra.pop("_pattern", {})
    uns = {"format_version": FORMAT_VERSION, "name": pattern.name, "units": "m"}
    uns.update(pattern.unsew)
    uns["format_version"] = FORMAT_VERSION
    uns["name"] = pattern.name
    if any(s.label for s in pattern.stitches):
        uns["stitch_labels"] = [s.label for s in pattern.stitches]
    out = {
        "pattern": {
            "panels": panels,
            "stitches": stitches,
            "panel_order": list(pattern.panel_order),
            **pat_extra,
        }
    }
    out.update(extra)
    out["properties"] = props
    out["unsew"] = uns
    return _jsonable(out)


def load_pattern(path: str | os.PathLike, *, validate: bool = True) -> Pattern:
    """Read a GarmentCode specification JSON file into a :class:`Pattern` (lengths in metres).

    Raises :class:`~unsew.errors.InputError` for a missing, empty or malformed file and
    :class:`~unsew.errors.PatternError` for a malformed pattern (with ``validate``).
    """
    path = Path(path)
    if not path.is_file():
        raise InputError(f"pattern file {path} not found; give the path of a GarmentCode JSON file")
    text = path.read_text(encoding="utf-8", errors="replace")
    if not text.strip():
        raise InputError(f"pattern file {path} is empty; give a GarmentCode specification JSON")
    try:
        data = json.loads(text)
    except json.JSONDecodeError as exc:
        raise InputError(
            f"pattern file {path} is not valid JSON (line {exc.lineno}, column {exc.colno}: {exc.msg})"
        ) from None
    stem = path.stem
    if stem.endswith("_specification"):
        stem = stem[: -len("_specification")]
    try:
        return pattern_from_dict(data, name=stem, validate=validate)
    except (InputError, PatternError) as exc:
        raise type(exc)(f"{path.name}: {exc}") from None


def save_pattern(pattern: Pattern, path: str | os.PathLike) -> None:
    """Write ``pattern`` as GarmentCode specification JSON, atomically (a temporary file in the
    same folder renamed onto ``path`` when complete)."""
    from unsew.io.atomic import atomic_write

    data = pattern_to_dict(pattern)
    text = json.dumps(data, indent=2, allow_nan=False)
    with atomic_write(path) as tmp:
        Path(tmp).write_text(text + "\n", encoding="utf-8")
