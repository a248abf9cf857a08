"""The sewing-pattern model (paper 3.2): panels, edges with curves, stitches.

Units: metres inside unsew. Panel vertices are 2D positions in the panel's own frame [m];
each panel has a 3D placement (translation [m], rotation as XYZ Euler angles [degrees],
GarmentCode's convention: a 2D point p maps to ``R @ (p_x, p_y, 0) + translation``).

A panel's outline is a closed counter-clockwise loop of edges: ``edges[i].end ==
edges[(i+1) % n].start`` and the signed area is positive. Edge curvature follows
GarmentCode's *relative* coordinates: a control point ``(s, t)`` of the edge from ``a`` to
``b`` sits at ``a + s*(b-a) + t*perp(b-a)`` with ``perp(x, y) = (-y, x)`` (a quarter turn
counter-clockwise). A circular arc is stored as ``(radius [m], large_arc, right)``:
the arc through ``a`` and ``b`` of that radius, the larger of the two arcs if ``large_arc``,
bulging to the right of ``a -> b`` if ``right``.

A stitch pairs two panel edges; by convention side ``a`` runs against side ``b`` (the
start of ``a`` is sewn to the end of ``b``), which is how two counter-clockwise panels facing
each other meet. Curve geometry (sampling, lengths) is in :mod:`unsew.pattern.curves`.
"""

from __future__ import annotations

import copy
from dataclasses import dataclass, field
from typing import Literal

import numpy as np

__all__ = [
    "Curvature",
    "Edge",
    "Panel",
    "StitchSide",
    "Stitch",
    "Pattern",
    "euler_xyz_to_matrix",
    "matrix_to_euler_xyz",
    "reverse_curvature",
    "mirror_curvature",
    "pattern_diff",
]

CurveKind = Literal["quadratic", "cubic", "circle"]


@dataclass
class Curvature:
    """Curvature of one edge, in GarmentCode's relative convention (see module docstring).

    ``quadratic``: ``params = [[s, t]]`` (one control point, relative).
    ``cubic``: ``params = [[s1, t1], [s2, t2]]`` (two control points, relative).
    ``circle``: ``params = [radius_m, large_arc, right]`` (radius in metres; two bools).
    """

    kind: CurveKind
    params: list
    extra: dict = field(default_factory=dict)  # unknown keys of the file's curvature dict, kept

    def copy(self) -> "Curvature":
        return Curvature(self.kind, copy.deepcopy(self.params), copy.deepcopy(self.extra))


@dataclass
class Edge:
    """One edge of a panel outline, from vertex ``start`` to vertex ``end`` (panel indices)."""

    start: int
    end: int
    curvature: Curvature | None = None
    label: str = ""
    extra: dict = field(default_factory=dict)  # unknown keys of the file's edge dict, kept

    def copy(self) -> "Edge":
        return Edge(
            self.start,
            self.end,
            self.curvature.copy() if self.curvature else None,
            self.label,
            copy.deepcopy(self.extra),
        )

    def reversed(self) -> "Edge":
        """The same curve traversed from ``end`` to ``start`` (curvature re-expressed)."""
        return Edge(
            self.end,
            self.start,
            reverse_curvature(self.curvature) if self.curvature else None,
            self.label,
            copy.deepcopy(self.extra),
        )


@dataclass
class Panel:
    """A pattern piece.

    vertices: 2D corner/join positions [m], shape (N, 2), float64.
    edges: closed counter-clockwise loop over the vertices.
    translation: 3D placement [m], shape (3,). rotation: XYZ Euler angles [deg], shape (3,).
    """

    name: str
    vertices: np.ndarray
    edges: list[Edge]
    translation: np.ndarray = field(default_factory=lambda: np.zeros(3))
    rotation: np.ndarray = field(default_factory=lambda: np.zeros(3))
    label: str = ""
    extra: dict = field(default_factory=dict)  # unknown keys of the file's panel dict, kept

    def rotation_matrix(self) -> np.ndarray:
        """The placement rotation, shape (3, 3), float64 (from ``rotation`` [deg, XYZ Euler])."""
        return euler_xyz_to_matrix(self.rotation)

    def to_world(self, points: np.ndarray) -> np.ndarray:
        """Panel-frame points (N, 2) [m] -> world positions (N, 3) [m]:
        ``R @ (x, y, 0) + translation``."""
        p = np.asarray(points, dtype=np.float64).reshape(-1, 2)
        p3 = np.concatenate([p, np.zeros((len(p), 1))], axis=1)
        return p3 @ self.rotation_matrix().T + self.translation

    def __post_init__(self) -> None:
        self.vertices = np.asarray(self.vertices, dtype=np.float64).reshape(-1, 2)
        self.translation = np.asarray(self.translation, dtype=np.float64).reshape(3)
        self.rotation = np.asarray(self.rotation, dtype=np.float64).reshape(3)

    def copy(self) -> "Panel":
        return Panel(
            self.name,
            self.vertices.copy(),
            [e.copy() for e in self.edges],
            self.translation.copy(),
            self.rotation.copy(),
            self.label,
            copy.deepcopy(self.extra),
        )


@dataclass(frozen=True)
class StitchSide:
    """One side of a stitch: edge number ``edge`` of panel ``panel``."""

    panel: str
    edge: int


@dataclass
class Stitch:
    """Two panel edges sewn together; ``a.start`` meets ``b.end`` (see module docstring)."""

    a: StitchSide
    b: StitchSide
    label: str = ""
    #: What the file carried beside panel/edge, kept for round trips: ``{"a": {...}, "b": {...}}``
    #: (extra keys of each side's dict) and ``"tail"`` (list entries after the two sides).
    extra: dict = field(default_factory=dict)


@dataclass
class Pattern:
    """A sewing pattern: named panels, stitches, and what GarmentCode or unsew keep beside them.

    properties: GarmentCode's ``properties`` block, kept for lossless round trips.
    unsew: unsew's own additions (control points, symmetry, material), written under the
    ``"unsew"`` key of the JSON so GarmentCode readers ignore it.
    """

    name: str
    panels: dict[str, Panel]
    stitches: list[Stitch] = field(default_factory=list)
    panel_order: list[str] = field(default_factory=list)
    properties: dict = field(default_factory=dict)
    unsew: dict = field(default_factory=dict)
    extra: dict = field(default_factory=dict)  # unknown top-level keys, written back unchanged

    def __post_init__(self) -> None:
        if not self.panel_order:
            self.panel_order = list(self.panels)

    def ordered_panels(self) -> list[Panel]:
        """Panels in ``panel_order`` (the order meshing and control points use)."""
        return [self.panels[n] for n in self.panel_order]

    def copy(self) -> "Pattern":
        return Pattern(
            self.name,
            {k: p.copy() for k, p in self.panels.items()},
            [Stitch(s.a, s.b, s.label, copy.deepcopy(s.extra)) for s in self.stitches],
            list(self.panel_order),
            copy.deepcopy(self.properties),
            copy.deepcopy(self.unsew),
            copy.deepcopy(self.extra),
        )


def euler_xyz_to_matrix(angles_deg) -> np.ndarray:
    """XYZ Euler angles [deg], shape (3,) -> rotation matrix (3, 3), float64.

    GarmentCode's convention (scipy's lowercase ``"xyz"``, extrinsic): rotate about the world X
    axis, then Y, then Z, i.e. ``R = Rz @ Ry @ Rx``.
    """
    ax, ay, az = np.radians(np.asarray(angles_deg, dtype=np.float64).reshape(3))
    cx, sx, cy, sy, cz, sz = np.cos(ax), np.sin(ax), np.cos(ay), np.sin(ay), np.cos(az), np.sin(az)
    rx = np.array([[1.0, 0.0, 0.0], [0.0, cx, -sx], [0.0, sx, cx]])
    ry = np.array([[cy, 0.0, sy], [0.0, 1.0, 0.0], [-sy, 0.0, cy]])
    rz = np.array([[cz, -sz, 0.0], [sz, cz, 0.0], [0.0, 0.0, 1.0]])
    return rz @ ry @ rx


def matrix_to_euler_xyz(R: np.ndarray) -> np.ndarray:
    """Inverse of :func:`euler_xyz_to_matrix`: rotation (3, 3) -> XYZ Euler angles [deg], (3,)."""
    R = np.asarray(R, dtype=np.float64)
    sy = -R[2, 0]
    if abs(sy) < 1.0 - 1e-12:
        ay = np.arcsin(sy)
        ax = np.arctan2(R[2, 1], R[2, 2])
        az = np.arctan2(R[1, 0], R[0, 0])
    else:  # gimbal lock: put all of the remaining turn into X
        ay = np.pi / 2 if sy > 0 else -np.pi / 2
        az = 0.0
        ax = np.arctan2(R[0, 1] * np.sign(sy), R[1, 1])
    return np.degrees(np.array([ax, ay, az]))


def reverse_curvature(c: Curvature) -> Curvature:
    """The curvature of the same curve traversed backwards (edge b -> a instead of a -> b).

    A relative point (s, t) of a->b is (1 - s, -t) of b->a; a cubic's two control points also
    swap; a circular arc keeps its radius and size and bulges to the other side of the
    reversed direction (``right`` flips).
    """
    if c.kind == "quadratic":
        ((s, t),) = c.params
        return Curvature("quadratic", [[1.0 - s, -t]], copy.deepcopy(c.extra))
    if c.kind == "cubic":
        (s1, t1), (s2, t2) = c.params
        return Curvature("cubic", [[1.0 - s2, -t2], [1.0 - s1, -t1]], copy.deepcopy(c.extra))
    if c.kind == "circle":
        r, large, right = c.params
        return Curvature("circle", [r, large, type(right)(not right)], copy.deepcopy(c.extra))
    raise ValueError(f"unknown curvature type {c.kind!r}")


def mirror_curvature(c: Curvature) -> Curvature:
    """The curvature of an edge's mirror image (any reflection), traversed from the mirrored
    start to the mirrored end: relative points (s, t) -> (s, -t); arcs flip ``right``."""
    if c.kind in ("quadratic", "cubic"):
        return Curvature(c.kind, [[s, -t] for s, t in c.params], copy.deepcopy(c.extra))
    if c.kind == "circle":
        r, large, right = c.params
        return Curvature("circle", [r, large, type(right)(not right)], copy.deepcopy(c.extra))
    raise ValueError(f"unknown curvature type {c.kind!r}")


def _diff_containers(a, b, where: str, atol: float, rtol: float, out: list[str]) -> bool:
    """:func:`_diff_values` of two dicts or two lists/tuples, entry by entry; False (nothing
    appended) when a and b are not such a pair."""
    if isinstance(a, dict) and isinstance(b, dict):
        if set(a) != set(b):
            out.append(f"{where}: keys {sorted(a)} != {sorted(b)}")
            return True
        for k in a:
            _diff_values(a[k], b[k], f"{where}.{k}", atol, rtol, out)
        return True
    if isinstance(a, (list, tuple)) and isinstance(b, (list, tuple)):
        if len(a) != len(b):
            out.append(f"{where}: length {len(a)} != {len(b)}")
            return True
        for i, (x, y) in enumerate(zip(a, b)):
            _diff_values(x, y, f"{where}[{i}]", atol, rtol, out)
        return True
    return False


def _diff_values(a, b, where: str, atol: float, rtol: float, out: list[str]) -> None:
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        a, b = np.asarray(a, dtype=np.float64), np.asarray(b, dtype=np.float64)
        if a.shape != b.shape:
            out.append(f"{where}: shape {a.shape} != {b.shape}")
        elif not np.allclose(a, b, atol=atol, rtol=rtol, equal_nan=True):
            out.append(f"{where}: values differ by up to {np.nanmax(np.abs(a - b)):.3g}")
        return
    if isinstance(a, (bool, str)) or isinstance(b, (bool, str)) or a is None or b is None:
        if type(a) is not type(b) or a != b:
            out.append(f"{where}: {a!r} != {b!r}")
        return
    if isinstance(a, (int, float)) and isinstance(b, (int, float)):
        if not abs(a - b) <= atol + rtol * abs(b):
            out.append(f"{where}: {a!r} != {b!r}")
        return
    if _diff_containers(a, b, where, atol, rtol, out):
        return
    if a != b:
        out.append(f"{where}: {a!r} != {b!r}")


def pattern_diff(p: Pattern, q: Pattern, *, atol: float = 0.0, rtol: float = 0.0) -> list[str]:
    """Differences between two patterns, one line each (empty when equal).

    Numbers [m, deg, relative] are compared with ``|a - b| <= atol + rtol*|b|``; everything else
    (names, labels, kinds, flags, extra keys, properties, ``unsew`` block) exactly.
    """
    out: list[str] = []
    _diff_values(p.name, q.name, "name", atol, rtol, out)
    _diff_values(list(p.panels), list(q.panels), "panels", atol, rtol, out)
    _diff_values(p.panel_order, q.panel_order, "panel_order", atol, rtol, out)
    for name in p.panels:
        if name not in q.panels:
            continue
        a, b = p.panels[name], q.panels[name]
        w = f"panel {name!r}"
        for attr in ("vertices", "translation", "rotation", "label", "extra"):
            _diff_values(getattr(a, attr), getattr(b, attr), f"{w}.{attr}", atol, rtol, out)
        if len(a.edges) != len(b.edges):
            out.append(f"{w}: {len(a.edges)} edges != {len(b.edges)}")
            continue
        for i, (ea, eb) in enumerate(zip(a.edges, b.edges)):
            we = f"{w} edge {i}"
            _diff_values([ea.start, ea.end, ea.label], [eb.start, eb.end, eb.label], we, atol, rtol, out)
            _diff_values(ea.extra, eb.extra, f"{we}.extra", atol, rtol, out)
            if (ea.curvature is None) != (eb.curvature is None):
                out.append(f"{we}: curvature {ea.curvature} != {eb.curvature}")
            elif ea.curvature is not None:
                ca, cb = ea.curvature, eb.curvature
                _diff_values(ca.kind, cb.kind, f"{we}.kind", atol, rtol, out)
                _diff_values(ca.params, cb.params, f"{we}.params", atol, rtol, out)
                _diff_values(ca.extra, cb.extra, f"{we}.curvature_extra", atol, rtol, out)
    if len(p.stitches) != len(q.stitches):
        out.append(f"stitches: {len(p.stitches)} != {len(q.stitches)}")
    else:
        for i, (sa, sb) in enumerate(zip(p.stitches, q.stitches)):
            if (sa.a, sa.b, sa.label) != (sb.a, sb.b, sb.label):
                out.append(f"stitch {i}: {sa} != {sb}")
            _diff_values(sa.extra, sb.extra, f"stitch {i}.extra", atol, rtol, out)
    for attr in ("properties", "unsew", "extra"):
        _diff_values(getattr(p, attr), getattr(q, attr), attr, atol, rtol, out)
    return out
